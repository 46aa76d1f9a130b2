#include "io/vtu_poly_writer.h"

#include <array>
#include <bit>
#include <charconv>
#include <cstring>
#include <ostream>
#include <set>
#include <type_traits>

#include "core/atomic_file.h"
#include "core/error.h"

namespace polydual {
namespace {

// Binary arrays are the in-memory bytes; the file declares LittleEndian.
static_assert(std::endian::native == std::endian::little, "vtu binary mode assumes little endian");

constexpr std::uint8_t kVtkPolyhedron = 42;

std::string base64(const std::vector<unsigned char>& in) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < in.size(); i += 3) {
    const std::uint32_t b0 = in[i];
    const std::uint32_t b1 = i + 1 < in.size() ? in[i + 1] : 0;
    const std::uint32_t b2 = i + 2 < in.size() ? in[i + 2] : 0;
    const std::uint32_t n = (b0 << 16) | (b1 << 8) | b2;
    out += kAlphabet[(n >> 18) & 63];
    out += kAlphabet[(n >> 12) & 63];
    out += i + 1 < in.size() ? kAlphabet[(n >> 6) & 63] : '=';
    out += i + 2 < in.size() ? kAlphabet[n & 63] : '=';
  }
  return out;
}

// One number as text. Doubles get 17 significant digits: that is the smallest
// count that makes every IEEE binary64 value round-trip through decimal exactly,
// so the reader recovers bit-identical coordinates (the validity test is exact,
// a rounded point could flip a cell's verdict). to_chars is locale-independent.
template <class T>
void put_number(std::string& s, T v) {
  std::array<char, 32> buf;
  std::to_chars_result r;
  if constexpr (std::is_floating_point_v<T>)
    r = std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::general, 17);
  else
    r = std::to_chars(buf.data(), buf.data() + buf.size(), static_cast<std::int64_t>(v));
  s.append(buf.data(), r.ptr);
}

template <class T>
void write_array(std::ostream& os, const char* type, const std::string& name, int components,
                 const std::vector<T>& v, bool binary, bool field_data = false) {
  os << "        <DataArray type=\"" << type << "\" Name=\"" << name << "\"";
  if (components > 1) os << " NumberOfComponents=\"" << components << "\"";
  if (field_data) os << " NumberOfTuples=\"" << v.size() << "\"";
  os << " format=\"" << (binary ? "binary" : "ascii") << "\">\n";
  if (binary) {
    // VTK's uncompressed layout: a UInt64 byte count, then the raw values,
    // base64-encoded together as one stream.
    const std::uint64_t bytes = v.size() * sizeof(T);
    std::vector<unsigned char> raw(sizeof bytes + bytes);
    std::memcpy(raw.data(), &bytes, sizeof bytes);
    if (bytes) std::memcpy(raw.data() + sizeof bytes, v.data(), bytes);
    os << "          " << base64(raw) << "\n";
  } else {
    const std::size_t per_line = components > 1 ? static_cast<std::size_t>(components) : 12;
    std::string line;
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (i % per_line == 0) line = "          ";
      else line += ' ';
      put_number(line, v[i]);
      if (i % per_line == per_line - 1 || i + 1 == v.size()) os << line << "\n";
    }
  }
  os << "        </DataArray>\n";
}

}  // namespace

void write_vtu_poly(const PolyMesh& mesh, const std::string& path,
                    const std::vector<CellField>& extra, const VtuOptions& options) {
  const std::size_t nc = mesh.num_cells(), np = mesh.num_points();
  std::set<std::string> names{"material", "primal_vertex"};
  for (const CellField& f : extra) {
    const std::size_t n = std::visit([](const auto& v) { return v.size(); }, f.values);
    if (n != nc)
      throw UsageError("write_vtu_poly: field '" + f.name + "' has " + std::to_string(n) +
                       " values for " + std::to_string(nc) + " cells");
    if (f.name.empty() || f.name.find_first_of("\"<>&") != std::string::npos ||
        !names.insert(f.name).second)
      throw UsageError("write_vtu_poly: bad or duplicate cell field name '" + f.name + "'");
  }

  // Assemble every array first, so the stream callback only formats.
  std::vector<double> coords;
  coords.reserve(3 * np);
  std::vector<std::int8_t> class_dim(np);
  std::vector<std::int32_t> class_tag(np);
  for (std::size_t i = 0; i < np; ++i) {
    coords.insert(coords.end(), {mesh.points[i].x, mesh.points[i].y, mesh.points[i].z});
    class_dim[i] = mesh.point_class[i].dim;
    class_tag[i] = mesh.point_class[i].tag;
  }
  std::vector<std::int64_t> conn, offsets, faces, face_offsets, primal(nc);
  std::vector<std::int32_t> face_kind, face_tag;
  for (std::size_t c = 0; c < nc; ++c) {
    const CellId cell(c);
    for (PointId p : mesh.cell_points(cell)) conn.push_back(p.idx);
    offsets.push_back(static_cast<std::int64_t>(conn.size()));
    faces.push_back(static_cast<std::int64_t>(mesh.cell(cell).size()));
    for (HalfFace h : mesh.cell(cell)) {
      const std::vector<PointId> loop = mesh.oriented_loop(h);
      faces.push_back(static_cast<std::int64_t>(loop.size()));
      for (PointId p : loop) faces.push_back(p.idx);
      face_kind.push_back(static_cast<std::int32_t>(mesh.face_kind[h.face().idx]));
      face_tag.push_back(mesh.face_tag[h.face().idx]);
    }
    face_offsets.push_back(static_cast<std::int64_t>(faces.size()));
    primal[c] = mesh.cell_primal[c].valid() ? mesh.cell_primal[c].idx : -1;
  }
  const std::vector<std::uint8_t> types(nc, kVtkPolyhedron);
  const bool bin = options.binary;

  write_file_atomically(path, [&](std::ostream& os) {
    os << "<?xml version=\"1.0\"?>\n"
       << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\""
       << " header_type=\"UInt64\">\n  <UnstructuredGrid>\n    <FieldData>\n";
    write_array(os, "Int32", "face_kind", 1, face_kind, bin, true);
    write_array(os, "Int32", "face_tag", 1, face_tag, bin, true);
    os << "    </FieldData>\n    <Piece NumberOfPoints=\"" << np << "\" NumberOfCells=\"" << nc
       << "\">\n      <PointData>\n";
    write_array(os, "Int8", "class_dim", 1, class_dim, bin);
    write_array(os, "Int32", "class_tag", 1, class_tag, bin);
    os << "      </PointData>\n      <CellData>\n";
    write_array(os, "Int32", "material", 1, mesh.cell_material, bin);
    write_array(os, "Int64", "primal_vertex", 1, primal, bin);
    for (const CellField& f : extra) {
      if (const auto* d = std::get_if<std::vector<double>>(&f.values))
        write_array(os, "Float64", f.name, 1, *d, bin);
      else
        write_array(os, "Int32", f.name, 1, std::get<std::vector<std::int32_t>>(f.values), bin);
    }
    os << "      </CellData>\n      <Points>\n";
    write_array(os, "Float64", "Points", 3, coords, bin);
    os << "      </Points>\n      <Cells>\n";
    write_array(os, "Int64", "connectivity", 1, conn, bin);
    write_array(os, "Int64", "offsets", 1, offsets, bin);
    write_array(os, "UInt8", "types", 1, types, bin);
    write_array(os, "Int64", "faces", 1, faces, bin);
    write_array(os, "Int64", "faceoffsets", 1, face_offsets, bin);
    os << "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  }, bin);
}

}  // namespace polydual
