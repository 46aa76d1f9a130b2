#include "io/medit_io.h"

#include <algorithm>
#include <cctype>
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

std::string lower(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return r;
}

// Keywords whose records are a fixed number of numbers and which carry nothing
// we use (feature hints, normals, surface elements we do not model): skipped.
int skipped_record_size(const std::string& kw) {
  static const std::pair<const char*, int> kSkip[] = {
      {"requiredvertices", 1}, {"ridges", 1},    {"requirededges", 1}, {"requiredtriangles", 1},
      {"requiredtetrahedra", 1}, {"normals", 3}, {"tangents", 3},      {"normalatvertices", 2},
      {"normalattrianglevertices", 3}, {"tangentatvertices", 2}, {"tangentatedges", 3}};
  for (const auto& [name, n] : kSkip)
    if (kw == name) return n;
  return 0;
}

bool is_unsupported_volume(const std::string& kw) {
  return kw == "tetrahedrap2";
}

// CGAL Mesh_3's output_to_medit with show_patches = false (its default)
// writes every boundary and interface triangle twice, with opposite
// orientations: an interface triangle with the lower then the higher subdomain
// on its sides as references, a boundary triangle twice with its inner
// subdomain (CGAL replaces the outside, 0, by the other side). Recognised when
// every triangle comes in such a pair (same vertices, opposite orientation,
// references that are region tags): each pair becomes one triangle whose
// model face is the pair of subdomains it separates, tagged 1, 2, ... in
// increasing (lower, higher) order, (r, r) standing for r and the outside.
struct SidedTriangle {
  std::array<std::uint32_t, 3> sorted;
  bool odd;  // the permutation sorting the written order is odd
  std::uint32_t index;
};

std::vector<SidedTriangle> sided(const std::vector<TaggedTriangle>& triangles) {
  std::vector<SidedTriangle> s(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    auto v = triangles[i].v;
    bool odd = false;
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2 - a; ++b)
        if (v[b] > v[b + 1]) std::swap(v[b], v[b + 1]), odd = !odd;
    s[i] = {v, odd, std::uint32_t(i)};
  }
  std::sort(s.begin(), s.end(), [](const SidedTriangle& a, const SidedTriangle& b) {
    return a.sorted != b.sorted ? a.sorted < b.sorted : a.index < b.index;
  });
  return s;
}

void merge_two_sided_triangles(TetSoup& soup) {
  const std::size_t n = soup.triangles.size();
  if (n == 0 || n % 2 != 0) return;
  std::vector<std::int32_t> regions(soup.tet_region);
  std::sort(regions.begin(), regions.end());
  auto is_region = [&](std::int32_t r) { return std::binary_search(regions.begin(), regions.end(), r); };
  const std::vector<SidedTriangle> s = sided(soup.triangles);
  std::vector<std::pair<std::int32_t, std::int32_t>> side_pair(n / 2);
  for (std::size_t k = 0; k < n; k += 2) {
    const SidedTriangle &a = s[k], &b = s[k + 1];
    if (a.sorted != b.sorted || a.odd == b.odd || (k + 2 < n && s[k + 2].sorted == a.sorted)) return;
    const std::int32_t ra = soup.triangles[a.index].tag, rb = soup.triangles[b.index].tag;
    if (!is_region(ra) || !is_region(rb)) return;
    side_pair[k / 2] = {std::min(ra, rb), std::max(ra, rb)};
  }
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs(side_pair);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  std::vector<TaggedTriangle> merged(n / 2);
  for (std::size_t k = 0; k < n; k += 2) {
    const auto tag = std::lower_bound(pairs.begin(), pairs.end(), side_pair[k / 2]) - pairs.begin() + 1;
    merged[k / 2] = {soup.triangles[std::min(s[k].index, s[k + 1].index)].v, std::int32_t(tag)};
  }
  soup.triangles = std::move(merged);
  std::string list;
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const auto [lo, hi] = pairs[p];
    const std::string sides = std::to_string(lo) + "|" + (lo == hi ? "outside" : std::to_string(hi));
    soup.groups.push_back({2, std::int32_t(p + 1), "subdomains " + sides, {std::int32_t(p + 1)}});
    if (p < 8) list += (p ? ", " : "") + std::to_string(p + 1) + " = " + sides;
  }
  if (pairs.size() > 8) list += ", ...";
  soup.warnings.push_back(soup.source + ": every triangle is written once per side (CGAL Mesh_3 output_to_medit, " +
                          "show_patches = false): merged into " + std::to_string(n / 2) +
                          " triangles tagged by the subdomains they separate (" + list + ")");
}

struct Reader {
  io::TextCursor cur;
  TetSoup soup;
  bool have_dimension = false;
  std::size_t vertices_line = 0, tetrahedra_line = 0;  // 0: no such section (yet)

  std::uint32_t vertex() {
    const std::int64_t n = static_cast<std::int64_t>(soup.points.size());
    if (n == 0) cur.fail("element refers to vertices but no Vertices were given before it");
    return static_cast<std::uint32_t>(cur.integer_in("vertex index", 1, n) - 1);
  }
  std::int32_t ref() {
    return static_cast<std::int32_t>(
        cur.integer_in("reference", std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::max()));
  }
  std::int64_t count(const char* keyword, std::size_t min_bytes) {
    const std::int64_t n = cur.integer_in("count", 0, std::numeric_limits<std::uint32_t>::max());
    cur.check_count(n, min_bytes, keyword);
    return n;
  }

  // One keyword's section; false for End.
  bool section(std::string_view word) {
    const std::string kw = lower(word);
    if (kw == "end") return false;
    if (kw == "meshversionformatted") {
      cur.integer_in("version", 1, 4);
    } else if (kw == "dimension") {
      const std::int64_t d = cur.integer("dimension");
      if (d != 3) cur.fail("Dimension " + std::to_string(d) + " not supported (only 3)");
      have_dimension = true;
    } else if (kw == "vertices") {
      if (vertices_line) cur.fail("second Vertices section");
      vertices_line = cur.line();
      vertices();
    } else if (kw == "tetrahedra") {
      if (!tetrahedra_line) tetrahedra_line = cur.line();
      tetrahedra();
    } else if (kw == "triangles") {
      triangles();
    } else if (kw == "edges") {
      edges();
    } else if (kw == "hexahedra" || kw == "prisms" || kw == "pyramids") {
      other_cells(kw == "hexahedra" ? CellType::Hex : kw == "prisms" ? CellType::Prism : CellType::Pyramid, word);
    } else if (kw == "quadrilaterals") {
      quadrilaterals();
    } else if (kw == "corners") {
      const std::int64_t n = count("Corners", 2);
      for (std::int64_t i = 0; i < n; ++i) {
        const std::uint32_t v = vertex();
        soup.corners.push_back({v, static_cast<std::int32_t>(v + 1)});
      }
    } else if (const int size = skipped_record_size(kw); size > 0) {
      const std::int64_t n = count(std::string(word).c_str(), 2 * size);
      for (std::int64_t i = 0; i < n * size; ++i) cur.real("value");
    } else if (is_unsupported_volume(kw)) {
      cur.fail("unsupported element kind " + std::string(word) + " (only linear tetrahedra, pyramids, prisms and hexahedra)");
    } else {
      cur.fail("unknown keyword '" + io::quoted(word) + "'");
    }
    return true;
  }

  void vertices() {
    const std::int64_t n = count("Vertices", 8);
    soup.points.reserve(n);
    for (std::int64_t i = 0; i < n; ++i) {
      Point3 p;
      for (int k = 0; k < 3; ++k) p[k] = cur.real("coordinate");
      cur.integer("vertex reference");
      soup.points.push_back(p);
    }
  }
  void tetrahedra() {
    const std::int64_t n = count("Tetrahedra", 10);
    for (std::int64_t i = 0; i < n; ++i) {
      std::array<std::uint32_t, 4> t{};
      for (auto& v : t) v = vertex();
      soup.tets.push_back(t);
      soup.tet_region.push_back(ref());
    }
  }
  void triangles() {
    const std::int64_t n = count("Triangles", 8);
    for (std::int64_t i = 0; i < n; ++i) {
      TaggedTriangle t;
      for (auto& v : t.v) v = vertex();
      if (const std::string bad = io::repeated_vertex(t.v, "triangle"); !bad.empty()) cur.fail(bad);
      t.tag = ref();
      soup.triangles.push_back(t);
    }
  }
  // Medit's vertex order is Gmsh's for these cells, up to a mirror image that
  // build_primal undoes (classify/classify_primal.h).
  void other_cells(CellType type, std::string_view word) {
    const int nv = descriptor(type).num_vertices;
    const std::int64_t n = count(std::string(word).c_str(), 2 * (nv + 1));
    for (std::int64_t i = 0; i < n; ++i) {
      SoupCell c{type, {}, 0, 0};
      for (int k = 0; k < nv; ++k) c.v[k] = vertex();
      c.region = ref();
      soup.other_cells.push_back(c);
    }
  }
  void quadrilaterals() {
    const std::int64_t n = count("Quadrilaterals", 10);
    for (std::int64_t i = 0; i < n; ++i) {
      TaggedQuad q;
      for (auto& v : q.v) v = vertex();
      q.tag = ref();
      soup.quads.push_back(q);
    }
  }
  void edges() {
    const std::int64_t n = count("Edges", 6);
    for (std::int64_t i = 0; i < n; ++i) {
      TaggedEdge e;
      for (auto& v : e.v) v = vertex();  // degenerate edges are dropped by drop_unattached
      e.tag = ref();
      soup.edges.push_back(e);
    }
  }

  [[noreturn]] void no_tetrahedra() const {
    if (tetrahedra_line)
      throw InputError(cur.source(), "line " + std::to_string(tetrahedra_line),
                       "the file holds no tetrahedra (its Tetrahedra section is empty)");
    const std::size_t others = soup.triangles.size() + soup.edges.size() + soup.corners.size();
    throw InputError(cur.source(), "end of file",
                     std::string("the file holds no tetrahedra (no ") +
                         (vertices_line ? "Tetrahedra section" : "Vertices and no Tetrahedra section") +
                         (others ? ", only " + io::count_of(others, "triangle, edge or corner", "triangles, edges and corners")
                                 : std::string()) + ")");
  }

  TetSoup read() {
    if (cur.at_end()) throw InputError(cur.source(), "", "the file is empty");
    while (!cur.at_end() && section(cur.token("keyword"))) {
    }
    // A file without tets (an empty Tetrahedra section, none at all as in a
    // surface mesh, or not even Vertices) holds no mesh to convert.
    if (!have_dimension) throw InputError(cur.source(), "end of file", "missing 'Dimension 3'");
    if (soup.tets.empty() && soup.other_cells.empty()) no_tetrahedra();
    if (!vertices_line) throw InputError(cur.source(), "end of file", "missing Vertices section");
    soup.source = cur.source();
    merge_two_sided_triangles(soup);
    io::drop_unattached(soup);
    return std::move(soup);
  }
};

}  // namespace

TetSoup read_medit(std::string_view bytes, const std::string& source) {
  Reader r{io::TextCursor(bytes, source, '#'), {}};
  return r.read();
}

TetSoup read_medit_file(const std::string& path) {
  io::InputFile file(path);
  Reader r{io::TextCursor(file, '#'), {}};
  return r.read();
}

void write_medit(const TetSoup& soup, const std::string& path) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << std::setprecision(17);
    out << "MeshVersionFormatted 2\nDimension 3\n\nVertices\n" << soup.points.size() << "\n";
    for (const Point3& p : soup.points) out << p.x << ' ' << p.y << ' ' << p.z << " 0\n";
    out << "\nTetrahedra\n" << soup.tets.size() << "\n";
    for (std::size_t i = 0; i < soup.tets.size(); ++i) {
      for (std::uint32_t v : soup.tets[i]) out << v + 1 << ' ';
      out << (i < soup.tet_region.size() ? soup.tet_region[i] : 1) << "\n";
    }
    if (!soup.triangles.empty()) {
      out << "\nTriangles\n" << soup.triangles.size() << "\n";
      for (const TaggedTriangle& t : soup.triangles)
        out << t.v[0] + 1 << ' ' << t.v[1] + 1 << ' ' << t.v[2] + 1 << ' ' << t.tag << "\n";
    }
    if (!soup.edges.empty()) {
      out << "\nEdges\n" << soup.edges.size() << "\n";
      for (const TaggedEdge& e : soup.edges) out << e.v[0] + 1 << ' ' << e.v[1] + 1 << ' ' << e.tag << "\n";
    }
    if (!soup.corners.empty()) {
      out << "\nCorners\n" << soup.corners.size() << "\n";
      for (const TaggedVertex& c : soup.corners) out << c.v + 1 << "\n";
    }
    out << "\nEnd\n";
  });
}

}  // namespace polydual
