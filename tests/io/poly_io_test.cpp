// Tests for the PolyMesh writers/readers (lib/io/vtu_poly_*, lib/io/foam_writer):
// hand-built hex meshes, VTU round trip and determinism, OpenFOAM ordering
// rules, zones, atomicity, and OpenFOAM's own checkMesh when it is installed.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <tuple>
#include <unistd.h>

#include "core/error.h"
#include "io/foam_writer.h"
#include "io/vtu_poly_reader.h"
#include "io/vtu_poly_writer.h"
#include "require_tool.h"
#include "vtu_text_edit.h"

namespace polydual {
namespace {

namespace fs = std::filesystem;

// An nx*ny*nz block of unit hexes. Interior faces between cells of different
// materials are Interface faces (tag 7); boundary faces are External with tag
// 1..6 (-x, +x, -y, +y, -z, +z). Cell c = i + nx*(j + ny*k), primal vertex = c.
PolyMesh hex_block(int nx, int ny, int nz, const std::vector<std::int32_t>& material) {
  PolyMesh m;
  auto pid = [&](int i, int j, int k) { return PointId(i + (nx + 1) * (j + (ny + 1) * k)); };
  auto cid = [&](int i, int j, int k) { return CellId(i + nx * (j + ny * k)); };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        const int on = (i == 0 || i == nx) + (j == 0 || j == ny) + (k == 0 || k == nz);
        m.add_point({0.1 * i, 0.1 * j + 1.0 / 3.0, 0.1 * k},
                    ModelRef{static_cast<std::int8_t>(3 - on), on});
      }
  std::vector<std::vector<HalfFace>> cells(static_cast<std::size_t>(nx * ny * nz));
  // The face at i/j/k = s on axis `axis`, spanning cell (a, b) in the other two;
  // its loop has a +axis normal (right-hand rule).
  auto add = [&](int axis, int s, int a, int b) {
    auto at = [&](int da, int db) {
      std::array<int, 3> q{};
      q[axis] = s;
      q[(axis + 1) % 3] = a + da;
      q[(axis + 2) % 3] = b + db;
      return pid(q[0], q[1], q[2]);
    };
    std::vector<PointId> loop{at(0, 0), at(1, 0), at(1, 1), at(0, 1)};
    const int n[3] = {nx, ny, nz};
    std::array<int, 3> below{}, above{};
    below[axis] = s - 1; above[axis] = s;
    below[(axis + 1) % 3] = above[(axis + 1) % 3] = a;
    below[(axis + 2) % 3] = above[(axis + 2) % 3] = b;
    if (s == 0 || s == n[axis]) {  // boundary: outward normal of the one cell
      const bool low = s == 0;
      const CellId c = low ? cid(above[0], above[1], above[2]) : cid(below[0], below[1], below[2]);
      if (low) std::reverse(loop.begin(), loop.end());
      const FaceId f = m.add_face(loop, c, CellId::invalid(), FaceKind::External, 2 * axis + (low ? 1 : 2));
      cells[c.idx].push_back(HalfFace(f, 0));
      return;
    }
    const CellId c0 = cid(below[0], below[1], below[2]), c1 = cid(above[0], above[1], above[2]);
    const bool iface = material[c0.idx] != material[c1.idx];
    const FaceId f = m.add_face(loop, c0, c1, iface ? FaceKind::Interface : FaceKind::Interior,
                                iface ? 7 : 0);
    cells[c0.idx].push_back(HalfFace(f, 0));
    cells[c1.idx].push_back(HalfFace(f, 1));
  };
  for (int s = 0; s <= nx; ++s) for (int a = 0; a < ny; ++a) for (int b = 0; b < nz; ++b) add(0, s, a, b);
  for (int s = 0; s <= ny; ++s) for (int a = 0; a < nz; ++a) for (int b = 0; b < nx; ++b) add(1, s, a, b);
  for (int s = 0; s <= nz; ++s) for (int a = 0; a < nx; ++a) for (int b = 0; b < ny; ++b) add(2, s, a, b);
  for (std::size_t c = 0; c < cells.size(); ++c) m.add_cell(cells[c], material[c], VertexId(c));
  return m;
}

PolyMesh unit_cube() { return hex_block(1, 1, 1, {4}); }
PolyMesh two_materials() { return hex_block(2, 1, 1, {1, 2}); }
PolyMesh block8() { return hex_block(2, 2, 2, std::vector<std::int32_t>(8, 1)); }

// The unit cube with an inner quad listed twice by its cell in opposite senses
// (a slit face, as at a fracture tip), on four points used by nothing else.
PolyMesh cube_with_slit() {
  PolyMesh m = hex_block(1, 1, 1, {4});
  std::vector<PointId> loop;
  for (auto [y, z] : {std::pair{0.3, 0.3}, {0.7, 0.3}, {0.7, 0.7}, {0.3, 0.7}})
    loop.push_back(m.add_point({0.05, 0.1 * y + 1.0 / 3.0, 0.1 * z}, ModelRef{2, 9}));
  const FaceId f = m.add_face(loop, CellId(0), CellId(0), FaceKind::Fracture, 9);
  m.cell_faces.push_back(HalfFace(f, 0));  // the cell is the last one: extend it
  m.cell_faces.push_back(HalfFace(f, 1));
  m.cell_offsets.back() += 2;
  return m;
}

// The unit cube whose first face passes twice through one of its corners with a
// spur out to an extra point, like the dual's caps through a model-edge midpoint:
// loop (b c d a b x) for the quad (a b c d).
PolyMesh cube_with_spur() {
  PolyMesh m = hex_block(1, 1, 1, {4});
  const PointId x = m.add_point({-0.05, 0.4, 0.05}, ModelRef{0, 3});
  std::vector<PointId> q(m.face(FaceId(0u)).begin(), m.face(FaceId(0u)).end());
  const std::vector<PointId> loop{q[1], q[2], q[3], q[0], q[1], x};
  m.face_points.erase(m.face_points.begin(), m.face_points.begin() + 4);
  m.face_points.insert(m.face_points.begin(), loop.begin(), loop.end());
  for (std::size_t f = 1; f < m.face_offsets.size(); ++f) m.face_offsets[f] += 2;
  return m;
}

fs::path scratch_root() {
  return fs::temp_directory_path() / ("polydual_poly_io_" + std::to_string(::getpid()));
}
// Removes this process's scratch directory once all tests have run.
struct ScratchCleanup : ::testing::Environment {
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(scratch_root(), ec);
  }
};
[[maybe_unused]] const auto* const kCleanup = ::testing::AddGlobalTestEnvironment(new ScratchCleanup);

fs::path scratch(const std::string& name) {
  fs::path p = scratch_root() / name;
  fs::remove_all(p);
  fs::create_directories(p.parent_path());
  return p;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A face identified by its cells and its loop up to rotation, in the owner's sense.
using FaceSig = std::tuple<std::uint32_t, std::uint32_t, std::vector<std::uint32_t>, int, int>;
std::multiset<FaceSig> face_signatures(const PolyMesh& m) {
  std::multiset<FaceSig> out;
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    std::vector<std::uint32_t> loop;
    for (PointId p : m.face(FaceId(f))) loop.push_back(p.idx);
    std::rotate(loop.begin(), std::min_element(loop.begin(), loop.end()), loop.end());
    out.insert({m.face_owner[f].idx, m.face_neighbour[f].idx, loop,
                static_cast<int>(m.face_kind[f]), m.face_tag[f]});
  }
  return out;
}

void expect_same_mesh(const PolyMesh& a, const PolyMesh& b) {
  ASSERT_EQ(a.num_points(), b.num_points());
  for (std::size_t i = 0; i < a.num_points(); ++i) {  // bit-exact coordinates
    EXPECT_EQ(std::memcmp(&a.points[i], &b.points[i], sizeof(Point3)), 0) << "point " << i;
    EXPECT_EQ(a.point_class[i], b.point_class[i]) << "point " << i;
  }
  EXPECT_EQ(a.cell_material, b.cell_material);
  EXPECT_EQ(a.cell_primal, b.cell_primal);
  EXPECT_EQ(face_signatures(a), face_signatures(b));
  ASSERT_EQ(a.num_cells(), b.num_cells());
  for (std::size_t c = 0; c < a.num_cells(); ++c)  // same outward loops per cell
    for (std::size_t k = 0; k < a.cell(CellId(c)).size(); ++k)
      EXPECT_EQ(a.oriented_loop(a.cell(CellId(c))[k]), b.oriented_loop(b.cell(CellId(c))[k]));
}

TEST(VtuPoly, RoundTripAsciiAndBinary) {
  for (bool binary : {false, true})
    for (const PolyMesh& m : {unit_cube(), two_materials(), block8(), cube_with_slit(), cube_with_spur()}) {
      const fs::path p = scratch(binary ? "m_bin.vtu" : "m.vtu");
      write_vtu_poly(m, p.string(), {}, VtuOptions{binary});
      expect_same_mesh(m, read_vtu_poly(p.string()));
    }
}

TEST(VtuPoly, SlitFaceComesBackAsOwnerEqualsNeighbour) {
  const fs::path p = scratch("slit.vtu");
  write_vtu_poly(cube_with_slit(), p.string());
  const PolyMesh r = read_vtu_poly(p.string());
  ASSERT_EQ(r.num_faces(), 7u);
  EXPECT_EQ(r.face_owner[6], r.face_neighbour[6]);
  EXPECT_EQ(r.face_kind[6], FaceKind::Fracture);
}

TEST(VtuPoly, ContentsAndExtraFields) {
  const PolyMesh m = two_materials();
  const fs::path p = scratch("extra.vtu");
  write_vtu_poly(m, p.string(),
                 {{"valid", std::vector<std::int32_t>{1, 0}}, {"q", std::vector<double>{0.5, 0.25}}});
  const std::string s = slurp(p);
  for (const char* needle :
       {"NumberOfPoints=\"12\" NumberOfCells=\"2\"", "Name=\"material\"", "Name=\"primal_vertex\"",
        "type=\"Int8\" Name=\"class_dim\"", "Name=\"class_tag\"", "Name=\"valid\"",
        "type=\"Float64\" Name=\"q\"", "Name=\"faceoffsets\"", "0.33333333333333331"})
    EXPECT_NE(s.find(needle), std::string::npos) << needle;
  EXPECT_THROW(write_vtu_poly(m, p.string(), {{"valid", std::vector<std::int32_t>{1}}}), UsageError);
  EXPECT_THROW(write_vtu_poly(m, p.string(), {{"material", std::vector<std::int32_t>{1, 1}}}),
               UsageError);
}

TEST(VtuPoly, DeterministicBytes) {
  for (bool binary : {false, true}) {
    const fs::path a = scratch("a.vtu"), b = scratch("b.vtu");
    write_vtu_poly(block8(), a.string(), {}, VtuOptions{binary});
    write_vtu_poly(block8(), b.string(), {}, VtuOptions{binary});
    EXPECT_EQ(slurp(a), slurp(b));
  }
}

TEST(VtuPoly, ReaderErrorsNameTheFile) {
  const fs::path p = scratch("bad.vtu");
  write_vtu_poly(unit_cube(), p.string());
  std::string s = slurp(p);
  const std::size_t types = s.find("Name=\"types\"");
  ASSERT_NE(types, std::string::npos);
  s.replace(s.find("42", types), 2, "12");  // a VTK_HEXAHEDRON, not a polyhedron
  std::ofstream(p) << s;
  try {
    read_vtu_poly(p.string());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), p.string());
    EXPECT_EQ(e.place(), "cell 0");
  }
  EXPECT_THROW(read_vtu_poly((p.parent_path() / "missing.vtu").string()), InputError);
}

using polydual::testing::with_array;

// The InputError of reading `bytes` ("(no error)" when it reads).
std::pair<std::string, std::string> read_error(const std::string& bytes) {
  try {
    read_vtu_poly_bytes(bytes, "corrupt.vtu");
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "corrupt.vtu");
    return {e.place(), e.what()};
  }
  return {"", "(no error)"};
}

// Each Cells array corrupted on its own (what VTK and ParaView read a cell
// from) is refused, naming the array and the cell.
TEST(VtuPoly, EveryCellsArrayIsCheckedAgainstTheOthers) {
  const fs::path p = scratch("arrays.vtu");
  write_vtu_poly(two_materials(), p.string());
  const std::string s = slurp(p);
  ASSERT_NO_THROW(read_vtu_poly_bytes(s, "corrupt.vtu"));
  using V = std::vector<std::string>;
  struct Case {
    const char* array;
    std::function<void(V&)> edit;
    const char* place;
    const char* what;
  };
  const Case cases[] = {
      {"connectivity", [](V& v) { v[0] = "-7"; }, "cell 0", "DataArray 'connectivity': point id -7 at index 0 out of range"},
      {"connectivity", [](V& v) { v[3] = "12"; }, "cell 0", "DataArray 'connectivity': point id 12 at index 3 out of range (12 points)"},
      {"offsets", [](V& v) { v[0] = "1000000000"; }, "cell 0", "DataArray 'offsets': value 1000000000 is beyond the end of 'connectivity' (16 values)"},
      {"offsets", [](V& v) { v[0] = "17"; v[1] = "16"; }, "cell 0", "beyond the end of 'connectivity'"},
      {"offsets", [](V& v) { v[0] = "9"; v[1] = "8"; }, "cell 1", "DataArray 'offsets': value 8 is below the previous cell's end 9"},
      {"offsets", [](V& v) { v[1] = "15"; }, "line", "DataArray 'offsets': the last cell ends at 15 but 'connectivity' has 16 values"},
      {"offsets", [](V& v) { v.pop_back(); }, "line", "DataArray 'offsets' has 1 values for 2 cells"},
      {"types", [](V& v) { v[1] = "12"; }, "cell 1", "DataArray 'types': type 12 is not a VTK_POLYHEDRON (42)"},
      {"types", [](V& v) { v.push_back("42"); }, "line", "DataArray 'types' has 3 values for 2 cells"},
      // A face count too high reads the next cell's record: faceoffsets disagrees.
      {"faces", [](V& v) { v[0] = "7"; }, "cell 0", "DataArray 'faceoffsets': value 31 but the cell's record in 'faces' ends at 38"},
      {"faces", [](V& v) { v.resize(v.size() - 3); }, "cell 1", "DataArray 'faces': face 5 has 4 points but the stream ends after 1"},
      {"faces", [](V& v) { v[1] = "2"; }, "cell 0", "DataArray 'faces': face 0 has 2 points (at least 3)"},
      {"faces", [](V& v) { v[2] = "99"; }, "cell 0", "DataArray 'faces': face 0 point id 99 at index 2 out of range"},
      {"faces", [](V& v) { v[0] = "0"; }, "cell 0", "DataArray 'faces': face count 0 at index 0 (at least 1)"},
      {"faceoffsets", [](V& v) { v[0] = "30"; }, "cell 0", "DataArray 'faceoffsets': value 30 but the cell's record in 'faces' ends at 31"},
      {"faceoffsets", [](V& v) { v.pop_back(); }, "line", "DataArray 'faceoffsets' has 1 values for 2 cells"},
      // connectivity against the faces: a point of another cell, one missing, one twice.
      {"connectivity", [](V& v) { v[0] = "2"; }, "cell 0", "DataArray 'connectivity': point 2 is on none of the cell's faces"},
      {"connectivity", [](V& v) { v[1] = v[0]; }, "cell 0", "DataArray 'connectivity': point 6 is listed twice"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.array) + ": " + c.what);
    const auto [place, what] = read_error(with_array(s, c.array, c.edit));
    EXPECT_EQ(place.rfind(c.place, 0), 0u) << place;
    EXPECT_NE(what.find(c.what), std::string::npos) << what;
  }
  // A point dropped from connectivity (the offsets follow): named as missing.
  std::string dropped = with_array(s, "connectivity", [](V& v) { v.erase(v.begin() + 8); });
  dropped = with_array(dropped, "offsets", [](V& v) { v[1] = "15"; });
  const auto [place, what] = read_error(dropped);
  EXPECT_EQ(place, "cell 1");
  EXPECT_NE(what.find("DataArray 'connectivity': point 1 of the cell's faces is missing"), std::string::npos) << what;
}

// A face is listed at most twice, in opposite senses: a third cell listing
// it (non-manifold) or a second listing in the same sense (two cells on one
// side of it) is refused, naming the cell.
TEST(VtuPoly, FaceOfThreeCellsOrTwiceInOneSenseIsRefused) {
  PolyMesh m = two_materials();
  FaceId shared = FaceId::invalid();
  for (std::size_t f = 0; f < m.num_faces(); ++f)
    if (m.face_neighbour[f].valid()) shared = FaceId(f);
  ASSERT_TRUE(shared.valid());
  PolyMesh three = m;  // a third cell made of the shared face alone
  three.add_cell(std::vector<HalfFace>{HalfFace(shared, 0)}, 5, VertexId(2u));
  const fs::path p = scratch("three.vtu");
  write_vtu_poly(three, p.string());
  auto [place, what] = read_error(slurp(p));
  EXPECT_EQ(place, "cell 2");
  EXPECT_NE(what.find("DataArray 'faces': face (points "), std::string::npos) << what;
  EXPECT_NE(what.find(" is already shared by cells 0 and 1: a face of three cells (non-manifold)"), std::string::npos)
      << what;
  PolyMesh same = m;  // cell 1 lists the shared face as cell 0 sees it
  for (HalfFace& h : same.cell_faces)
    if (h == HalfFace(shared, 1)) h = HalfFace(shared, 0);
  write_vtu_poly(same, p.string());
  std::tie(place, what) = read_error(slurp(p));
  EXPECT_EQ(place, "cell 1");
  EXPECT_NE(what.find(" is listed in the same sense by cell 0: two cells on one side of a face"), std::string::npos)
      << what;
}

// Every writer option: ascii; inline base64 and appended raw, each
// uncompressed and zlib at levels 1 and 9.
std::vector<std::pair<std::string, VtuOptions>> every_vtu_option() {
  std::vector<std::pair<std::string, VtuOptions>> out{{"ascii", VtuOptions{}}};
  for (int level : {0, 1, 9}) {
    out.push_back({"binary_z" + std::to_string(level), VtuOptions{true, false, level}});
    out.push_back({"appended_z" + std::to_string(level), VtuOptions{false, true, level}});
  }
  return out;
}

TEST(VtuPoly, RoundTripEveryWriterOption) {
  for (const auto& [name, options] : every_vtu_option())
    for (const PolyMesh& m : {unit_cube(), two_materials(), block8(), cube_with_slit(), cube_with_spur(), PolyMesh{}}) {
      SCOPED_TRACE(name);
      const fs::path p = scratch(name + ".vtu");
      write_vtu_poly(m, p.string(), {{"q", std::vector<double>(m.num_cells(), 0.5)}}, options);
      expect_same_mesh(m, read_vtu_poly(p.string()));
      const std::string s = slurp(p);
      EXPECT_EQ(s.find("<AppendedData encoding=\"raw\">") != std::string::npos, options.appended);
      EXPECT_EQ(s.find("compressor=\"vtkZLibDataCompressor\"") != std::string::npos, options.zlib_level > 0);
      EXPECT_EQ(s.find("format=\"binary\"") != std::string::npos, options.binary && !options.appended);
    }
}

TEST(VtuPoly, CompressionShrinksAndLevelsDiffer) {
  const PolyMesh m = hex_block(6, 6, 6, std::vector<std::int32_t>(216, 1));
  auto size_of = [&](const VtuOptions& o) {
    const fs::path p = scratch("size.vtu");
    write_vtu_poly(m, p.string(), {}, o);
    return fs::file_size(p);
  };
  const auto raw = size_of({false, true, 0}), z1 = size_of({false, true, 1}), z9 = size_of({false, true, 9});
  EXPECT_LT(z9, raw / 3);
  EXPECT_LE(z9, z1);
  EXPECT_LT(size_of({true, false, 9}), size_of({true, false, 0}) / 3);
}

// The bytes of the default options (ascii, and the binary the command writes)
// are pinned: tests/data/poly_twomat_{ascii,binary}.vtu were written before
// the appended/zlib options existed.
TEST(VtuPoly, DefaultOptionsBytesUnchanged) {
  const std::vector<CellField> extra{{"valid", std::vector<std::int32_t>{1, 0}}, {"bad_tets", std::vector<std::int32_t>{0, 3}}};
  for (bool binary : {false, true}) {
    const fs::path p = scratch("pinned.vtu");
    write_vtu_poly(two_materials(), p.string(), extra, VtuOptions{binary});
    EXPECT_EQ(slurp(p), slurp(fs::path(POLYDUAL_TEST_DATA) / (binary ? "poly_twomat_binary.vtu" : "poly_twomat_ascii.vtu")))
        << (binary ? "binary" : "ascii");
  }
}

TEST(VtuPoly, BadOptionsAreUsageErrors) {
  const fs::path p = scratch("opt.vtu");
  EXPECT_THROW(write_vtu_poly(unit_cube(), p.string(), {}, VtuOptions{false, false, 6}), UsageError);
  EXPECT_THROW(write_vtu_poly(unit_cube(), p.string(), {}, VtuOptions{true, false, 10}), UsageError);
  EXPECT_THROW(write_vtu_poly(unit_cube(), p.string(), {}, VtuOptions{false, true, -1}), UsageError);
  EXPECT_FALSE(fs::exists(p));
}

TEST(VtuPoly, DeterministicBytesEveryOption) {
  for (const auto& [name, options] : every_vtu_option()) {
    const fs::path a = scratch("a.vtu"), b = scratch("b.vtu");
    write_vtu_poly(block8(), a.string(), {}, options);
    write_vtu_poly(block8(), b.string(), {}, options);
    EXPECT_EQ(slurp(a), slurp(b)) << name;
  }
}

// Every prefix of a file of each option is an InputError, never a crash.
TEST(VtuPoly, EveryTruncationIsAnInputError) {
  for (const auto& [name, options] : every_vtu_option()) {
    const fs::path p = scratch("cut.vtu");
    write_vtu_poly(cube_with_slit(), p.string(), {}, options);
    const std::string s = slurp(p);
    const std::size_t end = s.rfind("</VTKFile>");
    for (std::size_t n = 0; n < end; ++n)
      EXPECT_THROW(read_vtu_poly_bytes(std::string_view(s).substr(0, n), "cut.vtu"), InputError) << name << " " << n;
  }
}

TEST(VtuPoly, ValuesOutOfRangeAreInputErrors) {
  const fs::path p = scratch("range.vtu");
  write_vtu_poly(unit_cube(), p.string());
  const std::string s = slurp(p);
  auto error_after = [&](const std::string& array, const std::string& from, const std::string& to) {
    std::string bad = s;
    const std::size_t at = bad.find(from, bad.find("Name=\"" + array + "\""));
    bad.replace(at, from.size(), to);
    try {
      read_vtu_poly_bytes(bad, "range.vtu");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_NE(error_after("class_dim", ">\n          0", ">\n          7").find("DataArray 'class_dim': value 7 at index 0 out of range (-1..3)"),
            std::string::npos);
  EXPECT_NE(error_after("material", ">\n          4", ">\n          4294967296")
                .find("DataArray 'material': value out of range of Int32 (4294967296)"),
            std::string::npos);
  EXPECT_NE(error_after("primal_vertex", ">\n          0", ">\n          4294967296")
                .find("DataArray 'primal_vertex': value 4294967296 at index 0 out of range (-1..2147483647)"),
            std::string::npos);
  EXPECT_NE(error_after("face_kind", ">\n          1", ">\n          9").find("DataArray 'face_kind': value 9"),
            std::string::npos);
}

// The regression seeds of the polyhedral VTU reader and its fuzzer
// (fuzz/regressions/vtu_poly_*: Cells arrays that disagree with each other,
// cases of EveryCellsArrayIsCheckedAgainstTheOthers kept as files so that
// fuzz/run.sh starts from them too) are read again: each is an InputError
// naming its file, never a mesh, a crash or another exception.
TEST(VtuPoly, FuzzRegressionsReplay) {
  const fs::path dir = fs::path(POLYDUAL_SOURCE_DIR) / "fuzz" / "regressions";
  ASSERT_TRUE(fs::is_directory(dir)) << dir;
  std::size_t n = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().filename().string().rfind("vtu_poly_", 0) != 0) continue;
    ++n;
    const std::string path = entry.path().string();
    try {
      read_vtu_poly(path);
      ADD_FAILURE() << path << " read as a mesh";
    } catch (const InputError& e) {
      EXPECT_EQ(e.source(), path);
    }
  }
  RecordProperty("replayed", static_cast<int>(n));
  EXPECT_GE(n, 4u) << "fewer fuzz/regressions/vtu_poly_* seeds than committed in " << dir;
}

// ---- OpenFOAM ------------------------------------------------------------------

// The entries of an OpenFOAM list file (labels or "n(...)" faces), one per line.
std::vector<std::string> foam_list(const fs::path& file) {
  std::istringstream in(slurp(file));
  std::string line;
  while (std::getline(in, line) && line != "(") {}
  std::vector<std::string> out;
  while (std::getline(in, line) && line != ")") out.push_back(line);
  return out;
}
std::vector<long> foam_labels(const fs::path& file) {
  std::vector<long> out;
  for (const std::string& s : foam_list(file)) out.push_back(std::stol(s));
  return out;
}

TEST(Foam, TwoMaterialsFilesOrderingZones) {
  const fs::path dir = scratch("twomat_case");
  const FoamReport r = write_foam(two_materials(), dir.string());
  const fs::path pm = dir / "constant" / "polyMesh";
  for (const char* f : {"points", "faces", "owner", "neighbour", "boundary", "cellZones", "faceZones"})
    EXPECT_TRUE(fs::exists(pm / f)) << f;
  for (const char* f : {"controlDict", "fvSchemes", "fvSolution"})
    EXPECT_TRUE(fs::exists(dir / "system" / f)) << f;
  EXPECT_EQ(r.points, 12u);
  EXPECT_EQ(r.cells, 2u);
  EXPECT_EQ(r.faces, 11u);
  EXPECT_EQ(r.internal_faces, 1u);
  EXPECT_EQ(r.patches, 6u);
  EXPECT_EQ(r.cell_zones, 2u);
  EXPECT_EQ(r.face_zones, 1u);
  EXPECT_EQ(foam_labels(pm / "neighbour"), std::vector<long>{1});
  EXPECT_EQ(foam_labels(pm / "owner").size(), 11u);
  EXPECT_NE(slurp(pm / "owner").find("note        \"nPoints:12  nCells:2  nFaces:11  nInternalFaces:1\""),
            std::string::npos);
  const std::string boundary = slurp(pm / "boundary");
  std::size_t last = 0;
  for (int tag = 1; tag <= 6; ++tag) {  // increasing tag order
    const std::size_t at = boundary.find("face_" + std::to_string(tag) + "\n");
    ASSERT_NE(at, std::string::npos);
    EXPECT_GT(at, last);
    last = at;
  }
  EXPECT_NE(boundary.find("face_3\n    {\n        type            patch;\n        nFaces          2;\n"
                          "        startFace       3;"),
            std::string::npos);  // -y: after the interface and the -x, +x faces
  EXPECT_NE(slurp(pm / "cellZones").find("material_1\n{\n    type cellZone;\ncellLabels      List<label> 1(0);"),
            std::string::npos);
  EXPECT_NE(slurp(pm / "cellZones").find("material_2"), std::string::npos);
  // The interface is oriented from material 1 to 2, which is owner -> neighbour here.
  EXPECT_NE(slurp(pm / "faceZones").find("interface_7\n{\n    type faceZone;\nfaceLabels      List<label> 1(0);\n"
                                         "flipMap         List<bool> 1(0);"),
            std::string::npos);
}

TEST(Foam, Block8UpperTriangularAndPatches) {
  PolyMesh m = block8();
  // Flip some internal faces (owner > neighbour) to exercise reorientation.
  for (std::size_t f = 0; f < m.num_faces(); f += 3) {
    if (!m.face_neighbour[f].valid()) continue;
    std::swap(m.face_owner[f], m.face_neighbour[f]);
    std::reverse(m.face_points.begin() + m.face_offsets[f], m.face_points.begin() + m.face_offsets[f + 1]);
    for (HalfFace& h : m.cell_faces)
      if (h.face().idx == f) h = h.opposite();
  }
  const fs::path dir = scratch("block8_case");
  const FoamReport r = write_foam(m, dir.string());
  const fs::path pm = dir / "constant" / "polyMesh";
  const auto owner = foam_labels(pm / "owner"), neighbour = foam_labels(pm / "neighbour");
  ASSERT_EQ(r.internal_faces, 12u);
  ASSERT_EQ(neighbour.size(), 12u);
  ASSERT_EQ(owner.size(), 36u);
  for (std::size_t i = 0; i < neighbour.size(); ++i) {
    EXPECT_LT(owner[i], neighbour[i]);
    if (i) EXPECT_LT(std::pair(owner[i - 1], neighbour[i - 1]), std::pair(owner[i], neighbour[i]));
  }
  // Every face's normal points out of its owner: the owner centre lies behind it.
  const auto pts = foam_list(pm / "points");
  const auto faces = foam_list(pm / "faces");
  auto point = [&](long i) {
    Point3 x;
    std::sscanf(pts[static_cast<std::size_t>(i)].c_str(), "(%lf %lf %lf)", &x.x, &x.y, &x.z);
    return x;
  };
  for (std::size_t f = 0; f < faces.size(); ++f) {
    std::istringstream in(faces[f].substr(2, faces[f].size() - 3));
    std::vector<Point3> q;
    for (long i; in >> i;) q.push_back(point(i));
    ASSERT_EQ(q.size(), 4u);
    const Vec3 n = cross(q[1] - q[0], q[2] - q[0]);
    const long c = owner[f];
    const Point3 centre{0.1 * (c % 2) + 0.05, 0.1 * (c / 2 % 2) + 0.05 + 1.0 / 3.0, 0.1 * (c / 4) + 0.05};
    EXPECT_GT(dot(n, q[0] - centre), 0) << "face " << f;
  }
  EXPECT_EQ(r.face_zones, 0u);
  EXPECT_EQ(r.patches, 6u);
}

// A slit face becomes a baffle: two boundary faces of its cell, the loop and its
// reverse, in the patch of its model face (tag 9), after the six wall patches.
TEST(Foam, SlitFacesBecomeTwoBoundaryFaces) {
  const fs::path dir = scratch("slit_case");
  const FoamReport r = write_foam(cube_with_slit(), dir.string());
  const fs::path pm = dir / "constant" / "polyMesh";
  EXPECT_EQ(r.slit_faces, 1u);
  EXPECT_EQ(r.dropped_points, 0u);
  EXPECT_EQ(r.points, 12u);
  EXPECT_EQ(r.faces, 8u);
  EXPECT_EQ(r.internal_faces, 0u);
  EXPECT_EQ(r.patches, 7u);
  EXPECT_NE(r.to_json().dump(0).find("\"slit_faces\":1"), std::string::npos) << r.to_json().dump(0);
  EXPECT_EQ(foam_list(pm / "points").size(), 12u);
  EXPECT_EQ(foam_labels(pm / "owner"), std::vector<long>(8, 0));
  const auto faces = foam_list(pm / "faces");
  ASSERT_EQ(faces.size(), 8u);
  // The last two faces are one loop in both senses, on the four slit points 8..11.
  auto loop_of = [](const std::string& f) {
    std::vector<long> v;
    std::istringstream in(f.substr(2, f.size() - 3));
    for (long x; in >> x;) v.push_back(x);
    return v;
  };
  const std::vector<long> a = loop_of(faces[6]), b = loop_of(faces[7]);
  ASSERT_EQ(a.size(), 4u);
  std::vector<long> sorted = a;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, (std::vector<long>{8, 9, 10, 11}));
  EXPECT_EQ(b, std::vector<long>(a.rbegin(), a.rend()));
  EXPECT_NE(slurp(pm / "boundary").find("face_9\n    {\n        type            patch;\n        nFaces          2;\n"
                                        "        startFace       6;"),
            std::string::npos) << slurp(pm / "boundary");
}

TEST(Foam, SpursAreCutOutOfFaces) {
  const fs::path dir = scratch("spur_case");
  const FoamReport r = write_foam(cube_with_spur(), dir.string());
  EXPECT_EQ(r.faces_without_spurs, 1u);
  EXPECT_EQ(r.dropped_points, 1u);
  const auto faces = foam_list(dir / "constant" / "polyMesh" / "faces");
  ASSERT_EQ(faces.size(), 6u);
  for (const std::string& f : faces) EXPECT_EQ(f.substr(0, 2), "4(") << f;
}

TEST(Foam, FailureLeavesNothing) {
  const fs::path base = scratch("atomic");
  fs::create_directories(base);
  std::ofstream(base / "file") << "x";
  EXPECT_ANY_THROW(write_foam(unit_cube(), (base / "file" / "case").string()));
  EXPECT_EQ(std::distance(fs::directory_iterator(base), fs::directory_iterator()), 1);

  // A bad mesh must not replace an existing case, nor leave a temporary behind.
  const fs::path dir = base / "case";
  write_foam(unit_cube(), dir.string());
  const std::string before = slurp(dir / "constant" / "polyMesh" / "faces");
  PolyMesh bad = unit_cube();
  bad.face_owner[2] = CellId::invalid();
  EXPECT_THROW(write_foam(bad, dir.string()), InputError);
  EXPECT_EQ(slurp(dir / "constant" / "polyMesh" / "faces"), before);
  EXPECT_EQ(std::distance(fs::directory_iterator(base), fs::directory_iterator()), 2);
}

// OpenFOAM's own checker, when installed (Debian package openfoam). Not -allGeometry:
// its cell-determinant check flags every cell with fewer than three internal
// directions, i.e. every cell of a tiny hand-built mesh, whatever the writer does.
std::string run_checkmesh(const fs::path& dir) {
  const fs::path log = dir.string() + ".checkMesh.log";
  const std::string cmd = "export WM_PROJECT_DIR=/usr/share/openfoam; /usr/bin/checkMesh -case '" +
                          dir.string() + "' -allTopology > '" + log.string() + "' 2>&1";
  const int rc = std::system(cmd.c_str());
  return "rc=" + std::to_string(rc) + "\n" + slurp(log);
}

TEST(Foam, CheckMeshAcceptsHandBuiltMeshes) {
  if (!fs::exists("/usr/bin/checkMesh") || !fs::exists("/usr/share/openfoam/etc/controlDict"))
    POLYDUAL_MISSING_TOOL("OpenFOAM (/usr/bin/checkMesh) is not installed (Debian package openfoam)");
  const std::map<std::string, PolyMesh> meshes{{"cube", unit_cube()}, {"twomat", two_materials()},
                                               {"block8", block8()}, {"slit", cube_with_slit()},
                                               {"spur", cube_with_spur()}};
  for (const auto& [name, m] : meshes) {
    const fs::path dir = scratch("check_" + name);
    write_foam(m, dir.string());
    const std::string out = run_checkmesh(dir);
    EXPECT_NE(out.find("rc=0\n"), std::string::npos) << name << "\n" << out;
    EXPECT_NE(out.find("Mesh OK."), std::string::npos) << name << "\n" << out;
    EXPECT_EQ(out.find("***"), std::string::npos) << name << "\n" << out;
  }
}

}  // namespace
}  // namespace polydual
