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
  if (params.num_points < 0) throw UsageError("random mesh: num_points must be >= 0");
  if (params.regions != 1 && params.regions != 2)
    throw UsageError("random mesh: regions must be 1 or 2");

  TetSoup soup;
  soup.source = "<random mesh seed " + std::to_string(params.seed) + ">";
  soup.full_classification = false;

  std::vector<Point3> input;
  for (int k = 0; k < 8; ++k)
    input.push_back({double(k & 1), double((k >> 1) & 1), double((k >> 2) & 1)});
  std::mt19937_64 rng(params.seed);
  for (int i = 0; i < params.num_points; ++i) {
    Point3 p{open_unit(rng()), open_unit(rng()), open_unit(rng())};
    if (params.lattice_points)
      for (int c = 0; c < 3; ++c) p[c] = std::floor(p[c] * 9.0) / 8.0;  // 0, 1/8, ..., 1
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

  if (params.fracture) {
    for (std::uint32_t a = 0; a < cells.size(); ++a) {
      const Point3 ga = centroid(soup.points, soup.tets[a]);
      for (int i = 0; i < 4; ++i) {
        auto nb = cells[a]->neighbor(i);
        if (dt.is_infinite(nb)) continue;
        const std::uint32_t b = cell_id.at(nb);
        if (b < a || soup.tet_region[a] != soup.tet_region[b]) continue;  // each pair once
        const Point3 gb = centroid(soup.points, soup.tets[b]);
        const bool first = ga.x < 0.6 && gb.x < 0.6 && ((ga.z < 0.5) != (gb.z < 0.5));
        const bool second = params.crossing_sheet && ga.x > 0.3 && gb.x > 0.3 && ((ga.y < 0.5) != (gb.y < 0.5));
        if (!first && !second) continue;
        TaggedTriangle f;
        for (int k = 0, j = 0; k < 4; ++k)
          if (k != i) f.v[j++] = cells[a]->vertex(k)->info();
        f.tag = first ? kRandomFractureTag : kRandomFractureTag + 1;  // one tag per triangle
        soup.triangles.push_back(f);
      }
    }
  }
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
