// Random Delaunay meshes and Kuhn lattices. The only translation unit that
// includes CGAL's Triangulation_3 (heavy to compile).
#include "generate/random_mesh.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <limits>
#include <random>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/error.h"
#include "predicates/predicates.h"

namespace polydual {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, K>;
using Tds = CGAL::Triangulation_data_structure_3<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_3<K, Tds>;

constexpr std::uint32_t kNoIndex = std::numeric_limits<std::uint32_t>::max();

// A double uniformly in the open interval (0, 1) from the top 53 bits of a
// 64-bit draw. mt19937_64's sequence is fixed by the standard; this mapping is
// ours, so the points are the same with every standard library.
double open_unit(std::uint64_t bits) {
  return (static_cast<double>(bits >> 11) + 0.5) * 0x1.0p-53;
}

// Positively orients t in place (exact); throws on a flat tet, which a
// generator must never produce.
void orient_positive(const std::vector<Point3>& pts, std::array<std::uint32_t, 4>& t,
                     const char* who) {
  const Sign s = orient3d(pts[t[0]], pts[t[1]], pts[t[2]], pts[t[3]]);
  if (s == Sign::Zero) throw std::logic_error(std::string(who) + ": flat tetrahedron");
  if (s == Sign::Negative) std::swap(t[2], t[3]);
}

Point3 centroid(const std::vector<Point3>& pts, const std::array<std::uint32_t, 4>& t) {
  return (pts[t[0]] + pts[t[1]] + pts[t[2]] + pts[t[3]]) / 4.0;
}

// Tag of the sheet triangle between two tets of one region with centroids ga
// and gb, or 0 if it is on no sheet (RandomMeshParams: fracture, crossing_sheet,
// network, fins). The first sheet that claims a triangle wins.
std::int32_t sheet_tag(const RandomMeshParams& p, const Point3& ga, const Point3& gb) {
  auto across = [&](int axis, double at) { return (ga[axis] < at) != (gb[axis] < at); };
  auto both_in = [&](int axis, double lo, double hi) {
    return ga[axis] > lo && ga[axis] < hi && gb[axis] > lo && gb[axis] < hi;
  };
  const bool fracture = p.fracture || p.network, crossing = p.crossing_sheet || p.network;
  if (fracture && both_in(0, -1, 0.6) && across(2, 0.5)) return kRandomFractureTag;
  if (fracture && crossing && both_in(0, 0.3, 2) && across(1, 0.5)) return kRandomFractureTag + 1;
  if (p.network && both_in(1, 0.2, 0.8) && both_in(2, 0.2, 0.8) && across(0, 0.5)) return kRandomFractureTag + 4;
  if (p.fins && both_in(0, -1, 0.35) && both_in(2, 0.25, 0.75) && across(1, 0.5)) return kRandomFractureTag + 2;
  if (p.fins && both_in(0, 0.65, 2) && both_in(1, 0.25, 0.75) && across(2, 0.5)) return kRandomFractureTag + 3;
  return 0;
}

bool in_notch(const Point3& g) { return g.x > 0.5 && g.y > 0.5 && g.z > 0.5; }

// RandomMeshParams::touching: the region of a tet with centroid g, 0 for a
// removed one.
std::int32_t touching_region(const Point3& g) {
  if (g.z < 0.5) return 1;
  if (g.x < 0.5 && g.y < 0.5) return 2;
  if (g.x > 0.5 && g.y > 0.5) return 3;
  return 0;
}

// Number of face-connected groups among `star` (tets sharing 3 vertices are
// neighbours); star is the set of kept tets around one vertex or edge.
std::size_t star_components(const TetSoup& soup, const std::vector<std::uint32_t>& star) {
  std::vector<std::size_t> group(star.size());
  for (std::size_t i = 0; i < star.size(); ++i) group[i] = i;
  auto root = [&](std::size_t i) {
    while (group[i] != i) i = group[i] = group[group[i]];
    return i;
  };
  for (std::size_t i = 0; i < star.size(); ++i)
    for (std::size_t j = i + 1; j < star.size(); ++j) {
      int shared = 0;
      for (auto a : soup.tets[star[i]])
        shared += static_cast<int>(std::count(soup.tets[star[j]].begin(), soup.tets[star[j]].end(), a));
      if (shared == 3) group[root(i)] = root(j);
    }
  std::size_t n = 0;
  for (std::size_t i = 0; i < star.size(); ++i) n += root(i) == i;
  return n;
}

// The centroid test cuts a Delaunay mesh that does not conform to the notch
// planes, so the kept tets can touch across the notch at a lone vertex or edge
// (a non-manifold domain). Such tets are put back, around every vertex and edge
// whose kept star falls apart, until none does (monotone, so it ends).
void keep_notch_manifold(const TetSoup& soup, std::vector<bool>& removed) {
  std::vector<std::vector<std::uint32_t>> tets_of(soup.points.size());
  for (std::uint32_t t = 0; t < soup.tets.size(); ++t)
    for (auto v : soup.tets[t]) tets_of[v].push_back(t);
  auto kept_star = [&](std::uint32_t v, std::uint32_t w) {  // w == kNoIndex: vertex star
    std::vector<std::uint32_t> star;
    for (auto t : tets_of[v])
      if (!removed[t] && (w == kNoIndex || std::count(soup.tets[t].begin(), soup.tets[t].end(), w)))
        star.push_back(t);
    return star;
  };
  auto restore = [&](std::uint32_t v, std::uint32_t w) {
    for (auto t : tets_of[v])
      if (w == kNoIndex || std::count(soup.tets[t].begin(), soup.tets[t].end(), w)) removed[t] = false;
  };
  for (bool changed = true; changed;) {
    changed = false;
    for (std::uint32_t v = 0; v < soup.points.size(); ++v) {
      if (star_components(soup, kept_star(v, kNoIndex)) > 1) restore(v, kNoIndex), changed = true;
      for (auto t : tets_of[v])
        for (auto w : soup.tets[t])
          if (w > v && star_components(soup, kept_star(v, w)) > 1) restore(v, w), changed = true;
    }
  }
}

// Drops the tets in `removed` and the points no remaining tet uses, renumbering
// the rest in order; sheet triangles on dropped tets were never listed.
void remove_tets(TetSoup& soup, const std::vector<bool>& removed) {
  std::vector<std::uint32_t> new_id(soup.points.size(), kNoIndex);
  std::vector<std::array<std::uint32_t, 4>> tets;
  std::vector<std::int32_t> regions;
  for (std::size_t t = 0; t < soup.tets.size(); ++t) {
    if (removed[t]) continue;
    tets.push_back(soup.tets[t]);
    regions.push_back(soup.tet_region[t]);
    for (auto v : soup.tets[t]) new_id[v] = 0;
  }
  std::vector<Point3> points;
  for (std::size_t v = 0; v < soup.points.size(); ++v)
    if (new_id[v] == 0) new_id[v] = static_cast<std::uint32_t>(points.size()), points.push_back(soup.points[v]);
  for (auto& t : tets)
    for (auto& v : t) v = new_id[v];
  for (auto& f : soup.triangles)
    for (auto& v : f.v) v = new_id[v];
  soup.points = std::move(points);
  soup.tets = std::move(tets);
  soup.tet_region = std::move(regions);
}

}  // namespace

namespace {
// See RandomMeshParams::unattached. The points are appended after the tets'
// vertices, so the tets' input numbering does not change.
void add_unattached(TetSoup& soup, bool with_sheet_part) {
  const auto base = static_cast<std::uint32_t>(soup.points.size());
  soup.points.push_back({0.5, 0.5, 1.5});
  soup.points.push_back({0.2, 0.8, 1.7});
  soup.points.push_back({0.9, 0.1, 1.6});
  soup.corners.push_back(TaggedVertex{base, kRandomUnattachedTag});
  soup.edges.push_back(TaggedEdge{{base, base + 1}, kRandomUnattachedTag + 1});
  soup.edges.push_back(TaggedEdge{{base + 2, base + 2}, kRandomUnattachedTag + 2});  // collapsed curve
  soup.triangles.push_back(TaggedTriangle{{base, base + 1, base + 2}, kRandomUnattachedTag + 3});
  if (with_sheet_part) soup.triangles.push_back(TaggedTriangle{{0, base, base + 1}, kRandomFractureTag});
}
}  // namespace

TetSoup random_classified_mesh(const RandomMeshParams& params) {
  if (params.num_points < 0 || params.face_points < 0)
    throw UsageError("random mesh: num_points and face_points must be >= 0");
  if (params.regions != 1 && params.regions != 2)
    throw UsageError("random mesh: regions must be 1 or 2");
  if (params.notch && params.touching)
    throw UsageError("random mesh: notch and touching exclude each other (the notch is kept manifold)");

  TetSoup soup;
  soup.source = "<random mesh seed " + std::to_string(params.seed) + ">";
  soup.full_classification = false;

  std::vector<Point3> input;
  for (int k = 0; k < 8; ++k)
    input.push_back({double(k & 1), double((k >> 1) & 1), double((k >> 2) & 1)});
  if (params.notch)  // the notch's corners, so its edges can be in the mesh
    for (int k = 0; k < 7; ++k)
      input.push_back({k & 1 ? 1.0 : 0.5, k & 2 ? 1.0 : 0.5, k & 4 ? 1.0 : 0.5});
  if (params.touching)  // the line where the upper blocks touch
    for (int k = 0; k <= 4; ++k) input.push_back({0.5, 0.5, 0.5 + 0.125 * k});
  std::mt19937_64 rng(params.seed);
  for (int i = 0; i < params.num_points; ++i) {
    Point3 p{open_unit(rng()), open_unit(rng()), open_unit(rng())};
    if (params.lattice_points)
      for (int c = 0; c < 3; ++c) p[c] = std::floor(p[c] * 9.0) / 8.0;  // 0, 1/8, ..., 1
    input.push_back(p);
  }
  for (int f = 0; f < 6; ++f)
    for (int i = 0; i < params.face_points; ++i) {
      Point3 p{open_unit(rng()), open_unit(rng()), open_unit(rng())};
      p[f / 2] = f % 2 ? 1.0 : 0.0;
      input.push_back(p);
    }

  // One insertion at a time, in input order: CGAL's range insert spatially
  // sorts with a randomised algorithm, and we want ids = first-insertion order.
  Delaunay dt;
  Delaunay::Cell_handle hint;
  for (const Point3& p : input) {
    const std::size_t before = dt.number_of_vertices();
    Delaunay::Vertex_handle v = dt.insert(K::Point_3(p.x, p.y, p.z), hint);
    if (dt.number_of_vertices() > before) {  // not a duplicate
      v->info() = static_cast<std::uint32_t>(soup.points.size());
      soup.points.push_back(p);
    }
    hint = v->cell();
  }
  if (dt.dimension() != 3) throw std::logic_error("random mesh: triangulation is not 3D");

  std::unordered_map<Delaunay::Cell_handle, std::uint32_t> cell_id;
  std::vector<Delaunay::Cell_handle> cells;
  for (auto c : dt.finite_cell_handles()) {
    std::array<std::uint32_t, 4> t{};
    for (int i = 0; i < 4; ++i) t[i] = c->vertex(i)->info();
    orient_positive(soup.points, t, "random mesh");
    cell_id.emplace(c, static_cast<std::uint32_t>(soup.tets.size()));
    cells.push_back(c);
    soup.tets.push_back(t);
    const Point3 g = centroid(soup.points, t);
    soup.tet_region.push_back(params.regions == 2 && g.x >= 0.5 ? 2 : 1);
  }

  std::vector<bool> removed(soup.tets.size(), false);
  if (params.touching)
    for (std::size_t t = 0; t < soup.tets.size(); ++t) {
      soup.tet_region[t] = touching_region(centroid(soup.points, soup.tets[t]));
      removed[t] = soup.tet_region[t] == 0;
    }
  if (params.notch) {
    for (std::size_t t = 0; t < soup.tets.size(); ++t) removed[t] = in_notch(centroid(soup.points, soup.tets[t]));
    keep_notch_manifold(soup, removed);
  }
  if (params.fracture || params.network || params.fins) {
    for (std::uint32_t a = 0; a < cells.size(); ++a) {
      const Point3 ga = centroid(soup.points, soup.tets[a]);
      for (int i = 0; i < 4; ++i) {
        auto nb = cells[a]->neighbor(i);
        if (dt.is_infinite(nb)) continue;
        const std::uint32_t b = cell_id.at(nb);
        if (b < a || soup.tet_region[a] != soup.tet_region[b]) continue;  // each pair once
        if (removed[a] || removed[b]) continue;
        const std::int32_t tag = sheet_tag(params, ga, centroid(soup.points, soup.tets[b]));
        if (tag == 0) continue;
        TaggedTriangle f;
        for (int k = 0, j = 0; k < 4; ++k)
          if (k != i) f.v[j++] = cells[a]->vertex(k)->info();
        f.tag = tag;
        soup.triangles.push_back(f);
      }
    }
  }
  if (params.notch || params.touching) remove_tets(soup, removed);
  if (params.unattached) add_unattached(soup, params.fracture);
  return soup;
}

TetSoup kuhn_lattice(int nx, int ny, int nz, double hx, double hy, double hz, int regions) {
  if (nx <= 0 || ny <= 0 || nz <= 0) throw UsageError("kuhn lattice: cell counts must be > 0");
  if (!(hx > 0 && hy > 0 && hz > 0)) throw UsageError("kuhn lattice: spacings must be > 0");
  if (regions != 1 && regions != 2) throw UsageError("kuhn lattice: regions must be 1 or 2");
  if (regions == 2 && nx % 2 != 0)
    throw UsageError("kuhn lattice: two regions split at the middle x plane need an even nx");

  TetSoup soup;
  soup.source = "<kuhn lattice " + std::to_string(nx) + "x" + std::to_string(ny) + "x" +
                std::to_string(nz) + ">";
  auto vid = [&](int i, int j, int k) {
    return static_cast<std::uint32_t>(i + (nx + 1) * (j + (ny + 1) * k));
  };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) soup.points.push_back({i * hx, j * hy, k * hz});

  // The 6 monotone lattice paths from corner (0,0,0) to (1,1,1) of a cell, one
  // per permutation of the axes: each is a tet, and together they tile the cell.
  static constexpr int kPerm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                      {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& perm : kPerm) {
          std::array<std::uint32_t, 4> t{};
          int c[3] = {i, j, k};
          t[0] = vid(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[perm[s]];
            t[s + 1] = vid(c[0], c[1], c[2]);
          }
          orient_positive(soup.points, t, "kuhn lattice");
          soup.tets.push_back(t);
          soup.tet_region.push_back(regions == 2 && 2 * i >= nx ? 2 : 1);
        }
  return soup;
}

}  // namespace polydual
