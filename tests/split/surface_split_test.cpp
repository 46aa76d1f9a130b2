// The split of surface duals (split/surface_split.h, dual/surface_dual.h's
// whole cuts; proofs/surface_dual.md S3): any set of vertices cut whole
// leaves the dual conformal and tiling its planar surfaces, every corner
// polygon is valid, and the split's rounds end with no invalid polygon on
// random surface networks (the model faces of random classified tet meshes:
// the box, jagged interfaces, fractures crossing and ending inside, fins),
// whose raw duals have invalid polygons.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <tuple>

#include "classify/classify.h"
#include "classify/classify_primal.h"
#include "dual/surface_dual.h"
#include "generate/random_mesh.h"
#include "mesh/cell_soup.h"
#include "mesh/model_facets.h"
#include "pipeline/convert_surface.h"
#include "quality/surface_verdict.h"
#include "split/surface_split.h"

namespace polydual {
namespace {

// Flips triangles so that each surface (tag) is coherently oriented: from
// each surface's first triangle, breadth first across the edges it shares
// with exactly one other triangle of the tag (every sheet here is a disk).
void orient_surfaces(TetSoup& soup) {
  std::map<std::tuple<std::int32_t, std::uint32_t, std::uint32_t>, std::vector<std::size_t>> by_edge;
  for (std::size_t t = 0; t < soup.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = soup.triangles[t].v[k], b = soup.triangles[t].v[(k + 1) % 3];
      by_edge[{soup.triangles[t].tag, std::min(a, b), std::max(a, b)}].push_back(t);
    }
  auto runs = [&](std::size_t t, std::uint32_t a, std::uint32_t b) {  // whether t's loop runs a -> b
    const auto& v = soup.triangles[t].v;
    for (int k = 0; k < 3; ++k)
      if (v[k] == a && v[(k + 1) % 3] == b) return true;
    return false;
  };
  std::vector<char> seen(soup.triangles.size(), 0);
  for (std::size_t start = 0; start < soup.triangles.size(); ++start) {
    if (seen[start]) continue;
    seen[start] = 1;
    std::vector<std::size_t> queue{start};
    while (!queue.empty()) {
      const std::size_t t = queue.back();
      queue.pop_back();
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = soup.triangles[t].v[k], b = soup.triangles[t].v[(k + 1) % 3];
        const auto& ts = by_edge[{soup.triangles[t].tag, std::min(a, b), std::max(a, b)}];
        if (ts.size() != 2) continue;
        const std::size_t u = ts[0] == t ? ts[1] : ts[0];
        if (seen[u]) continue;
        seen[u] = 1;
        if (runs(u, a, b)) std::swap(soup.triangles[u].v[0], soup.triangles[u].v[1]);
        queue.push_back(u);
      }
    }
  }
}

// The model faces of a random classified tet mesh (as classify() infers
// them: the box's six faces, the jagged interface, the fractures), without
// its tets: a surface network with curves where three or more sheets meet.
TetSoup random_network(std::uint64_t seed) {
  RandomMeshParams p;
  p.seed = seed;
  p.num_points = 40 + int(seed % 3) * 20;
  p.face_points = 6;
  p.regions = seed % 2 == 0 ? 2 : 1;
  p.fracture = seed % 3 != 2;
  p.crossing_sheet = seed % 3 == 1;
  p.fins = seed % 4 == 3;
  const ModelFacets f = model_facets(classify(random_classified_mesh(p)));
  TetSoup soup;
  soup.source = "<random network " + std::to_string(seed) + ">";
  soup.points = f.points;
  for (const ModelFacet& t : f.triangles) soup.triangles.push_back({{t.v[0].idx, t.v[1].idx, t.v[2].idx}, t.tag});
  orient_surfaces(soup);
  return soup;
}

// Each dual edge is used by two polygons in opposite directions, unless both
// its points lie on model curves (the network's boundary and crossings).
void expect_conformal(const PolySurface& s, const std::string& what) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<bool>> uses;
  for (std::size_t i = 0; i < s.num_polygons(); ++i) {
    const auto p = s.polygon(i);
    for (std::size_t k = 0; k < p.size(); ++k) {
      const std::uint32_t a = p[k], b = p[(k + 1) % p.size()];
      uses[{std::min(a, b), std::max(a, b)}].push_back(a < b);
    }
  }
  for (const auto& [e, dirs] : uses) {
    if (s.point_class(e.first).dim <= 1 && s.point_class(e.second).dim <= 1) continue;
    ASSERT_EQ(dirs.size(), 2u) << what << ": dual edge " << e.first << "-" << e.second;
    EXPECT_NE(dirs[0], dirs[1]) << what << ": dual edge " << e.first << "-" << e.second;
  }
}

TEST(SurfaceSplit, WholeCutsStayConformalTileThePlanesAndMakeValidCorners) {
  for (std::uint64_t seed = 0; seed < 6; ++seed) {
    const PrimalMesh m = build_primal(cell_soup(random_network(seed)));
    std::mt19937_64 rng(seed);
    for (int fraction : {0, 30, 100}) {
      std::vector<char> whole(m.num_vertices(), 0);
      std::size_t corners = 0;
      for (std::size_t v = 0; v < m.num_vertices(); ++v)
        if (int(rng() % 100) < fraction) whole[v] = 1, corners += m.vertex_cells(VertexId(v)).size();
      const std::string what = "seed " + std::to_string(seed) + ", " + std::to_string(fraction) + " % whole";
      const PolySurface s = build_surface_dual(m, &whole);
      expect_conformal(s, what);
      const SurfaceAreaIdentity a = surface_area_identity(m, s);
      EXPECT_GT(a.planar, 0u) << what;
      EXPECT_LE(a.max_rel_error, 1e-12) << what;
      const SurfaceVerdicts v = surface_verdicts(s);
      std::map<std::uint64_t, VertexId> vertex;  // input numbering -> the primal's
      for (std::size_t k = 0; k < m.num_vertices(); ++k) vertex[m.input_vertex(VertexId(k))] = VertexId(k);
      std::size_t whole_polygons = 0;
      for (std::size_t i = 0; i < s.num_polygons(); ++i) {
        const bool corner = whole[vertex.at(s.primal_vertex(i)).idx] != 0;
        whole_polygons += corner;
        if (corner) EXPECT_TRUE(v.valid[i]) << what << ": corner polygon " << i;
      }
      EXPECT_EQ(whole_polygons, corners) << what;
      if (fraction == 100) EXPECT_EQ(v.invalid, 0u) << what;
    }
  }
}

TEST(SurfaceSplit, RoundsEndWithEveryPolygonValid) {
  std::size_t raw_invalid = 0, rounds = 0;
  for (std::uint64_t seed = 0; seed < 12; ++seed) {
    const TetSoup soup = random_network(seed);
    for (int sweeps : {0, 4}) {
      SurfaceConvertParams params;
      params.smooth.sweeps = sweeps;
      params.split = false;
      const SurfaceConvertResult plain = convert_surface(soup, params);
      params.split = true;
      const SurfaceConvertResult r = convert_surface(soup, params);
      const std::string what = soup.source + (sweeps ? " smoothed" : " raw");
      EXPECT_EQ(r.verdicts.invalid, 0u) << what;
      EXPECT_LE(r.areas.max_rel_error, 1e-12) << what;
      expect_conformal(r.dual, what);
      raw_invalid += plain.verdicts.invalid;
      if (plain.verdicts.invalid == 0) {
        EXPECT_EQ(r.dual.num_polygons(), plain.dual.num_polygons()) << what << ": no split needed";
        continue;
      }
      const Json* n = r.split.find("rounds");
      ASSERT_NE(n, nullptr) << what;
      rounds += std::stoul(n->dump());
      EXPECT_GT(r.dual.num_polygons(), plain.dual.num_polygons()) << what;
    }
  }
  // Random Delaunay points make obtuse triangles: the raw duals need the split.
  EXPECT_GT(raw_invalid, 10u);
  EXPECT_GT(rounds, 0u);
}

TEST(SurfaceSplit, WithoutTheSplitInvalidPolygonsStay) {
  SurfaceConvertParams params;
  params.smooth.sweeps = 0;
  params.split = false;
  std::size_t invalid = 0;
  for (std::uint64_t seed = 0; seed < 12; ++seed) {
    const SurfaceConvertResult r = convert_surface(random_network(seed), params);
    invalid += r.verdicts.invalid;
    EXPECT_EQ(r.split.find("rounds"), nullptr);
  }
  EXPECT_GT(invalid, 0u);
}

}  // namespace
}  // namespace polydual
