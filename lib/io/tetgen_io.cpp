#include "io/tetgen_io.h"

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <ostream>

#include "core/atomic_file.h"
#include "core/file_type.h"
#include "io/file_bytes.h"
#include "io/record_checks.h"
#include "io/text_cursor.h"
#include "io/unattached.h"

namespace polydual {
namespace {

constexpr std::int64_t kMaxCount = std::numeric_limits<std::uint32_t>::max();

// An attribute that must hold an integer tag, although TetGen writes
// attributes as reals ("1", "1.0000000000000000e+00").
std::int32_t integer_attribute(io::TextCursor& cur, const char* what) {
  const double v = cur.real(what);
  if (v != std::floor(v) || v < std::numeric_limits<std::int32_t>::min() || v > std::numeric_limits<std::int32_t>::max())
    cur.fail(std::string(what) + " is not an integer (" + std::to_string(v) + ")");
  return static_cast<std::int32_t>(v);
}

// A count of the first line; 0 is an empty file (an error when `required`:
// without nodes or tets the files hold no tetrahedra). `item` names one.
std::int64_t header_count(io::TextCursor& cur, const char* what, const char* item, bool required) {
  if (cur.at_end()) throw InputError(cur.source(), "", "the file is empty");
  const std::int64_t n = cur.integer_in(what, 0, kMaxCount);
  if (n == 0 && required) cur.fail(std::string("the file holds no tetrahedra (its ") + item + " count is 0)");
  return n;
}

std::int64_t read_nodes(io::TextCursor& cur, TetSoup& soup) {
  const std::int64_t n = header_count(cur, "number of nodes", "node", true);
  const std::int64_t dim = cur.integer("dimension");
  if (dim != 3) cur.fail("dimension " + std::to_string(dim) + " not supported (only 3)");
  const std::int64_t nattr = cur.integer_in("number of attributes", 0, 1000);
  const std::int64_t bmark = cur.integer_in("boundary marker flag", 0, 1);
  cur.check_count(n, 8 + 2 * (nattr + bmark), "node");
  soup.points.reserve(n);
  std::int64_t base = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t idx = i == 0 ? cur.integer_in("first node index", 0, 1) : cur.integer("node index");
    if (i == 0) base = idx;
    if (idx != base + i)
      cur.fail("node index " + std::to_string(idx) + " out of sequence (expected " + std::to_string(base + i) + ")");
    Point3 p;
    for (int k = 0; k < 3; ++k) p[k] = cur.real("coordinate");
    for (std::int64_t k = 0; k < nattr; ++k) cur.real("node attribute");
    if (bmark) cur.integer("boundary marker");
    soup.points.push_back(p);
  }
  if (!cur.at_end()) {
    cur.token("");
    cur.fail("more data after the " + std::to_string(n) + " nodes announced");
  }
  return base;
}

std::uint32_t vertex(io::TextCursor& cur, std::int64_t base, std::size_t n) {
  return static_cast<std::uint32_t>(cur.integer_in("node index", base, base + static_cast<std::int64_t>(n) - 1) - base);
}

void read_elements(io::TextCursor& cur, std::int64_t base, TetSoup& soup) {
  const std::int64_t n = header_count(cur, "number of tetrahedra", "tetrahedron", true);
  const std::int64_t per_tet = cur.integer("nodes per tetrahedron");
  if (per_tet != 4) cur.fail("tetrahedra with " + std::to_string(per_tet) + " nodes not supported (only linear, 4)");
  const std::int64_t nattr = cur.integer_in("number of attributes", 0, 1000);
  cur.check_count(n, 10 + 2 * nattr, "tetrahedron");
  soup.tets.reserve(n);
  soup.tet_region.reserve(n);
  for (std::int64_t i = 0; i < n; ++i) {
    cur.integer("tetrahedron index");
    std::array<std::uint32_t, 4> t{};
    for (auto& v : t) v = vertex(cur, base, soup.points.size());
    std::int32_t region = 1;
    for (std::int64_t k = 0; k < nattr; ++k) {
      const std::int32_t a = integer_attribute(cur, "region attribute");
      if (k == 0) region = a;
    }
    soup.tets.push_back(t);
    soup.tet_region.push_back(region);
  }
  if (!cur.at_end()) {
    cur.token("");
    cur.fail("more data after the " + std::to_string(n) + " tetrahedra announced");
  }
}

void read_faces(io::TextCursor& cur, std::int64_t base, TetSoup& soup) {
  const std::int64_t n = header_count(cur, "number of faces", "face", false);
  const std::int64_t bmark = cur.integer_in("boundary marker flag", 0, 1);
  cur.check_count(n, 8 + 2 * bmark, "face");
  for (std::int64_t i = 0; i < n; ++i) {
    cur.integer("face index");
    TaggedTriangle t;
    for (auto& v : t.v) v = vertex(cur, base, soup.points.size());
    if (const std::string bad = io::repeated_vertex(t.v, "face"); !bad.empty()) cur.fail(bad);
    if (bmark)
      t.tag = static_cast<std::int32_t>(cur.integer_in("boundary marker", std::numeric_limits<std::int32_t>::min(),
                                                       std::numeric_limits<std::int32_t>::max()));
    // TetGen -nn adds two adjacent-tet columns: skip what remains on the line.
    cur.rest_of_line();
    soup.triangles.push_back(t);
  }
  if (!cur.at_end()) {
    cur.token("");
    cur.fail("more data after the " + std::to_string(n) + " faces announced");
  }
}

TetSoup finished(TetSoup soup, const std::string& basename) {
  soup.source = basename + ".ele";
  io::drop_unattached(soup);
  return soup;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

std::string tetgen_basename(const std::string& path) {
  for (const char* ext : {".node", ".ele", ".face"})
    if (ends_with(path, ext)) return path.substr(0, path.size() - std::string(ext).size());
  return path;
}

TetSoup read_tetgen(std::string_view node, std::string_view ele, std::optional<std::string_view> face,
                    const std::string& basename) {
  TetSoup soup;
  io::TextCursor node_cur(node, basename + ".node", '#');
  const std::int64_t base = read_nodes(node_cur, soup);
  io::TextCursor ele_cur(ele, basename + ".ele", '#');
  read_elements(ele_cur, base, soup);
  if (face) {
    io::TextCursor face_cur(*face, basename + ".face", '#');
    read_faces(face_cur, base, soup);
  }
  return finished(std::move(soup), basename);
}

// Each file is opened and read in turn, so a bad .node is refused before the
// .ele is opened.
TetSoup read_tetgen_files(const std::string& path) {
  const std::string base = tetgen_basename(path);
  TetSoup soup;
  std::int64_t first = 0;
  {
    io::InputFile node(base + ".node");
    io::TextCursor cur(node, '#');
    first = read_nodes(cur, soup);
  }
  {
    io::InputFile ele(base + ".ele");
    io::TextCursor cur(ele, '#');
    read_elements(cur, first, soup);
  }
  // A .face is optional; when present in any form it must be readable.
  if (file_type_no_follow(base + ".face") != FileType::Missing) {
    io::InputFile face(base + ".face");
    io::TextCursor cur(face, '#');
    read_faces(cur, first, soup);
  }
  return finished(std::move(soup), base);
}

void write_tetgen(const TetSoup& soup, const std::string& path) {
  const std::string base = tetgen_basename(path);
  write_file_atomically(base + ".node", [&](std::ostream& out) {
    out << std::setprecision(17) << soup.points.size() << " 3 0 0\n";
    for (std::size_t i = 0; i < soup.points.size(); ++i)
      out << i + 1 << ' ' << soup.points[i].x << ' ' << soup.points[i].y << ' ' << soup.points[i].z << "\n";
  });
  write_file_atomically(base + ".ele", [&](std::ostream& out) {
    out << soup.tets.size() << " 4 1\n";
    for (std::size_t i = 0; i < soup.tets.size(); ++i) {
      out << i + 1;
      for (std::uint32_t v : soup.tets[i]) out << ' ' << v + 1;
      out << ' ' << (i < soup.tet_region.size() ? soup.tet_region[i] : 1) << "\n";
    }
  });
  if (soup.triangles.empty()) {
    // A stale .face beside the new files would be read back with them.
    std::error_code ec;
    std::filesystem::remove(base + ".face", ec);
  } else {
    write_file_atomically(base + ".face", [&](std::ostream& out) {
      out << soup.triangles.size() << " 1\n";
      for (std::size_t i = 0; i < soup.triangles.size(); ++i) {
        const TaggedTriangle& t = soup.triangles[i];
        out << i + 1 << ' ' << t.v[0] + 1 << ' ' << t.v[1] + 1 << ' ' << t.v[2] + 1 << ' ' << t.tag << "\n";
      }
    });
  }
}

}  // namespace polydual
