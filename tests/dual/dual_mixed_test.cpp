// The dual of a PrimalMesh (dual/primal_dual.h): on tet meshes the same
// cells as the tet builder (the strongest check of its rules), and on hex,
// prism and pyramid meshes closed, valid cells with the expected volumes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "classify/classify.h"
#include "classify/classify_primal.h"
#include "dual/build_dual.h"
#include "dual/primal_dual.h"
#include "generate/random_mesh.h"
#include "mesh/cell_soup.h"
#include "mesh/validate.h"
#include "quality/star_verdict.h"

namespace polydual {
namespace {

// The tet soup of a classified tet mesh with its whole classification given
// (model faces, edges and vertices with their tags, internal numbering), so
// that build_primal() classifies it as classify() did.
TetSoup classified_soup(const ClassifiedTetMesh& m) {
  TetSoup s;
  s.source = "classified";
  s.points = m.points();
  for (std::size_t t = 0; t < m.num_tets(); ++t) {
    const auto& v = m.tet(TetId(t));
    s.tets.push_back({v[0].idx, v[1].idx, v[2].idx, v[3].idx});
    s.tet_region.push_back(m.region(TetId(t)));
  }
  for (std::size_t f = 0; f < m.num_triangles(); ++f)
    if (m.on_model_face(TriId(f))) {
      const auto& v = m.triangle(TriId(f));
      s.triangles.push_back({{v[0].idx, v[1].idx, v[2].idx}, m.triangle_class(TriId(f)).tag});
    }
  for (std::size_t e = 0; e < m.num_edges(); ++e)
    if (m.edge_class(EdgeId(e)).dim == 1)
      s.edges.push_back({{m.edge(EdgeId(e))[0].idx, m.edge(EdgeId(e))[1].idx}, m.edge_class(EdgeId(e)).tag});
  for (std::size_t v = 0; v < m.num_vertices(); ++v)
    if (m.vertex_class(VertexId(v)).dim == 0) s.corners.push_back({std::uint32_t(v), m.vertex_class(VertexId(v)).tag});
  return s;
}

// A cell seen from outside its numbering: its volume and its points' sorted coordinates.
struct CellPrint {
  double volume = 0;
  std::vector<Point3> points;
};

std::vector<Point3> cell_points(const PolyMesh& pm, CellId c) {
  std::vector<Point3> pts;
  for (std::uint32_t h = pm.cell_offsets[c.idx]; h < pm.cell_offsets[c.idx + 1]; ++h) {
    const FaceId f = pm.cell_faces[h].face();
    for (std::uint32_t k = pm.face_offsets[f.idx]; k < pm.face_offsets[f.idx + 1]; ++k)
      pts.push_back(pm.points[pm.face_points[k].idx]);
  }
  auto less = [](const Point3& a, const Point3& b) {
    return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
  };
  std::sort(pts.begin(), pts.end(), less);
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  return pts;
}

// Per primal vertex (by `vertex_of` of its cell_primal), its cells sorted by volume.
std::map<std::uint32_t, std::vector<CellPrint>> prints(const PolyMesh& pm, const std::vector<VertexId>& vertex_of) {
  std::map<std::uint32_t, std::vector<CellPrint>> out;
  for (std::size_t c = 0; c < pm.num_cells(); ++c)
    out[vertex_of.empty() ? pm.cell_primal[c].idx : vertex_of[pm.cell_primal[c].idx].idx].push_back(
        {cell_volume(pm, CellId(c)), cell_points(pm, CellId(c))});
  for (auto& [v, cells] : out)
    std::sort(cells.begin(), cells.end(), [](const CellPrint& a, const CellPrint& b) { return a.volume < b.volume; });
  return out;
}

void expect_same_dual(const PolyMesh& tet, const PolyMesh& mixed, const ClassifiedTetMesh& m, const std::string& what) {
  ASSERT_EQ(tet.num_cells(), mixed.num_cells()) << what;
  ASSERT_EQ(tet.num_faces(), mixed.num_faces()) << what;
  EXPECT_EQ(tet.num_points(), mixed.num_points()) << what;
  const auto a = prints(tet, internal_of_input(m)), b = prints(mixed, {});
  ASSERT_EQ(a.size(), b.size()) << what;
  for (const auto& [v, cells] : a) {
    const auto& other = b.at(v);
    ASSERT_EQ(cells.size(), other.size()) << what << " vertex " << v;
    for (std::size_t k = 0; k < cells.size(); ++k) {
      // Relative to the cell's volume, or to the box's for a sliver cell whose
      // volume is a cancelling sum (the same points give volumes of 1e-11
      // differing by 1e-20 when the cell's faces start their loops elsewhere).
      EXPECT_NEAR(cells[k].volume, other[k].volume, 1e-12 * std::max(std::fabs(cells[k].volume), 1e-6))
          << what << " vertex " << v;
      ASSERT_EQ(cells[k].points.size(), other[k].points.size()) << what << " vertex " << v;
      for (std::size_t p = 0; p < cells[k].points.size(); ++p)
        EXPECT_LT(norm(cells[k].points[p] - other[k].points[p]), 1e-12) << what << " vertex " << v;
    }
  }
}

RandomMeshParams family(std::uint64_t seed) {
  RandomMeshParams p;
  p.seed = seed;
  p.num_points = 60 + int(seed % 3) * 40;
  p.regions = seed % 2 == 0 ? 2 : 1;
  p.fracture = seed % 3 != 0;
  p.crossing_sheet = seed % 5 == 1;
  p.network = seed % 7 == 3;
  p.fins = seed % 4 == 2;
  p.notch = seed % 6 == 4;
  p.lattice_points = seed % 8 == 5;
  p.touching = seed % 6 == 5;  // edges of several chains (never with the notch: seed % 6 == 4)
  return p;
}

TEST(DualMixed, SameDualAsTheTetBuilderOnRandomMeshes) {
  for (std::uint64_t seed = 1; seed <= 18; ++seed)
    for (bool cleanup : {false, true})
      for (BoundaryMode mode : {BoundaryMode::Caps, BoundaryMode::Keep}) {
        const ClassifiedTetMesh m = classify(random_classified_mesh(family(seed)));
        const PrimalMesh pm = build_primal(cell_soup(classified_soup(m)));
        DualParams dp;
        dp.cleanup = cleanup;
        dp.boundary = mode;
        const std::string what = "seed " + std::to_string(seed) + (cleanup ? " cleanup" : " raw") + " " +
                                 boundary_mode_name(mode);
        expect_same_dual(build_dual(m, dp), build_primal_dual(pm, dp), m, what);
      }
}

}  // namespace
}  // namespace polydual
