#include "io/tetgen_io.h"

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <ostream>

#include "core/atomic_file.h"
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

std::int64_t read_nodes(std::string_view bytes, const std::string& source, TetSoup& soup) {
  io::TextCursor cur(bytes, source, '#');
  const std::int64_t n = cur.integer_in("number of nodes", 1, kMaxCount);
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

void read_elements(std::string_view bytes, const std::string& source, std::int64_t base, TetSoup& soup) {
  io::TextCursor cur(bytes, source, '#');
  const std::int64_t n = cur.integer_in("number of tetrahedra", 1, kMaxCount);
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

void read_faces(std::string_view bytes, const std::string& source, std::int64_t base, TetSoup& soup) {
  io::TextCursor cur(bytes, source, '#');
  const std::int64_t n = cur.integer_in("number of faces", 0, kMaxCount);
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
  const std::int64_t base = read_nodes(node, basename + ".node", soup);
  read_elements(ele, basename + ".ele", base, soup);
  if (face) read_faces(*face, basename + ".face", base, soup);
  soup.source = basename + ".ele";
  io::drop_unattached(soup);
  return soup;
}

TetSoup read_tetgen_files(const std::string& path) {
  const std::string base = tetgen_basename(path);
  const std::string node = io::read_file_bytes(base + ".node");
  const std::string ele = io::read_file_bytes(base + ".ele");
  std::optional<std::string> face;
  if (io::file_exists(base + ".face")) face = io::read_file_bytes(base + ".face");
  return read_tetgen(node, ele, face ? std::optional<std::string_view>(*face) : std::nullopt, base);
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
