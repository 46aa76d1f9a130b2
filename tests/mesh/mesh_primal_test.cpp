// PrimalMesh (mesh/primal_mesh.h): the cell descriptors on the reference
// elements, one cell of each type walked by the same queries, mixed blocks
// built at test time, the non-conformal quadrangle, and agreement with
// ClassifiedTetMesh on random tet meshes.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "classify/classify.h"
#include "classify/classify_primal.h"
#include "core/error.h"
#include "dual/primal_central_points.h"
#include "generate/random_mesh.h"
#include "mesh/cell_soup.h"
#include "predicates/predicates.h"

using namespace polydual;

namespace {

// Gmsh's reference elements (positively oriented).
std::vector<Point3> reference(CellType t) {
  switch (t) {
    case CellType::Tet: return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    case CellType::Pyramid: return {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {0, 0, 1}};
    case CellType::Prism: return {{0, 0, -1}, {1, 0, -1}, {0, 1, -1}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
    case CellType::Hex:
      return {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}};
    case CellType::Triangle: return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    case CellType::Quad: return {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  }
  return {};
}

CellSoup one_cell(CellType t) {
  CellSoup s;
  s.source = "<one " + std::string(cell_type_name(t)) + ">";
  s.points = reference(t);
  std::vector<std::uint32_t> v(s.points.size());
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = std::uint32_t(i);
  s.add_cell(t, v, 1);
  return s;
}

// The loop of face f as cell c sees it (outward from c).
std::vector<VertexId> loop_from(const PrimalMesh& m, PrimalFaceId f, PrimalCellId c) {
  const auto fv = m.face_vertices(f);
  std::vector<VertexId> l(fv.begin(), fv.end());
  if (m.face_cell(f, 0) != c) std::reverse(l.begin(), l.end());
  return l;
}
bool runs(const std::vector<VertexId>& l, VertexId a, VertexId b) {
  for (std::size_t k = 0; k < l.size(); ++k)
    if (l[k] == a && l[(k + 1) % l.size()] == b) return true;
  return false;
}

// The invariants every primal must satisfy, through the queries Algorithm 1
// uses. Returns the number of boundary faces.
std::size_t walk(const PrimalMesh& m) {
  // Stars: c is in vertex_cells(v) iff v is a vertex of c.
  std::size_t incidences = 0;
  for (std::size_t v = 0; v < m.num_vertices(); ++v)
    for (PrimalCellId c : m.vertex_cells(VertexId(v))) {
      EXPECT_GE(m.local_index(c, VertexId(v)), 0);
      ++incidences;
    }
  std::size_t expected = 0, boundary = 0;
  for (std::size_t c = 0; c < m.num_cells(); ++c) expected += m.cell_vertices(PrimalCellId(c)).size();
  EXPECT_EQ(incidences, expected);
  // Faces: shared whole by one or two cells, outward from each (EXACT).
  for (std::size_t c = 0; c < m.num_cells() && m.dim() == 3; ++c) {
    const PrimalCellId cc(c);
    Point3 inside{0, 0, 0};  // the vertex mean: strictly inside a convex cell
    for (VertexId v : m.cell_vertices(cc)) inside += m.point(v) * (1.0 / double(m.cell_vertices(cc).size()));
    for (int i = 0; i < m.cell_descriptor(cc).num_faces; ++i) {
      const PrimalFaceId f = m.cell_face(cc, i);
      EXPECT_EQ(m.face_cell(f, m.cell_face_side(cc, i)), cc);
      const PrimalCellId n = m.cell_neighbor(cc, i);
      if (!n.valid()) ++boundary;
      const auto l = loop_from(m, f, cc);
      for (std::size_t k = 0; k < l.size(); ++k)
        EXPECT_EQ(orient3d(m.point(l[k]), m.point(l[(k + 1) % l.size()]), m.point(l[(k + 2) % l.size()]), inside),
                  Sign::Negative)
            << "face " << f.idx << " of cell " << c << " is not outward";
    }
  }
  // Edges: every cell around e in exactly one chain; consecutive cells share
  // the face between them, which runs a->b seen from the cell before it.
  for (std::size_t e = 0; e < m.num_edges(); ++e) {
    const auto [a, b] = m.edge(EdgeId(e));
    for (PrimalCellId c : m.edge_cells(EdgeId(e))) EXPECT_TRUE(m.local_index(c, a) >= 0 && m.local_index(c, b) >= 0);
    if (m.dim() != 3) continue;
    std::multiset<PrimalCellId> seen;
    for (const EdgeChain& ch : m.edge_chains(EdgeId(e))) {
      EXPECT_EQ(ch.faces.size(), ch.cells.size() + 1);
      EXPECT_EQ(ch.closed, ch.faces.front() == ch.faces.back());
      if (!ch.closed) {
        EXPECT_FALSE(m.face_cell(ch.faces.front(), 1).valid());
        EXPECT_FALSE(m.face_cell(ch.faces.back(), 1).valid());
      }
      for (std::size_t k = 0; k < ch.cells.size(); ++k) {
        seen.insert(ch.cells[k]);
        EXPECT_TRUE(runs(loop_from(m, ch.faces[k], ch.cells[k]), b, a));
        EXPECT_TRUE(runs(loop_from(m, ch.faces[k + 1], ch.cells[k]), a, b));
      }
    }
    const auto around = m.edge_cells(EdgeId(e));
    EXPECT_EQ(seen, std::multiset<PrimalCellId>(around.begin(), around.end()));
  }
  return boundary;
}

}  // namespace

TEST(CellDescriptors, ReferenceElementsArePositiveWithOutwardClosedFaces) {
  for (CellType t : {CellType::Tet, CellType::Pyramid, CellType::Prism, CellType::Hex}) {
    const CellDescriptor& d = descriptor(t);
    const auto p = reference(t);
    SCOPED_TRACE(std::string(d.name));
    ASSERT_EQ(int(p.size()), d.num_vertices);
    for (int k = 0; k < d.num_corners; ++k) {
      const auto& q = d.corners[k];
      EXPECT_EQ(orient3d(p[q[0]], p[q[1]], p[q[2]], p[q[3]]), Sign::Positive) << "corner " << k;
    }
    // Every directed edge of a face loop is a descriptor edge, and each edge
    // is run once each way: the faces close the cell.
    std::map<std::pair<int, int>, int> runs_of;
    for (int i = 0; i < d.num_faces; ++i)
      for (int k = 0; k < d.face_size[i]; ++k) ++runs_of[{d.faces[i][k], d.faces[i][(k + 1) % d.face_size[i]]}];
    EXPECT_EQ(int(runs_of.size()), 2 * d.num_edges);
    for (int k = 0; k < d.num_edges; ++k) {
      EXPECT_EQ((runs_of[{d.edges[k][0], d.edges[k][1]}]), 1);
      EXPECT_EQ((runs_of[{d.edges[k][1], d.edges[k][0]}]), 1);
    }
    // The mirror permutation turns the cell negative, corner by corner.
    std::vector<Point3> mirrored(p.size());
    for (int i = 0; i < d.num_vertices; ++i) mirrored[i] = p[d.mirror[i]];
    for (int k = 0; k < d.num_corners; ++k) {
      const auto& q = d.corners[k];
      EXPECT_EQ(orient3d(mirrored[q[0]], mirrored[q[1]], mirrored[q[2]], mirrored[q[3]]), Sign::Negative);
    }
  }
}

TEST(PrimalMesh, OneCellOfEachTypeWalkedByTheSameQueries) {
  for (int ti = 0; ti < kNumCellTypes; ++ti) {
    const CellType t = CellType(ti);
    const CellDescriptor& d = descriptor(t);
    SCOPED_TRACE(std::string(d.name));
    const PrimalMesh m = build_primal(one_cell(t));
    EXPECT_EQ(m.dim(), d.dim);
    EXPECT_EQ(int(m.num_vertices()), d.num_vertices);
    EXPECT_EQ(int(m.num_edges()), d.num_edges);
    EXPECT_EQ(int(m.num_faces()), d.num_faces);
    for (std::size_t v = 0; v < m.num_vertices(); ++v) ASSERT_EQ(m.vertex_cells(VertexId(v)).size(), 1u);
    EXPECT_EQ(int(walk(m)), d.num_faces);  // every face on the boundary
    for (std::size_t e = 0; e < m.num_edges(); ++e) {
      EXPECT_EQ(m.edge_cells(EdgeId(e)).size(), 1u);
      if (d.dim != 3) continue;
      const auto chains = m.edge_chains(EdgeId(e));
      ASSERT_EQ(chains.size(), 1u);
      EXPECT_FALSE(chains[0].closed);
      EXPECT_NE(chains[0].faces[0], chains[0].faces[1]);
    }
    // Classification: one region; boundary faces (volume) or edges (surface)
    // on the model, one model face or edge all round (no features).
    EXPECT_EQ(m.cell_class(PrimalCellId(0u)), (ModelRef{std::int8_t(d.dim), 1}));
    for (std::size_t f = 0; f < m.num_faces(); ++f) EXPECT_EQ(m.face_class(PrimalFaceId(f)).dim, 2);
    for (std::size_t e = 0; e < m.num_edges(); ++e) EXPECT_EQ(m.edge_class(EdgeId(e)).dim, d.dim == 3 ? 2 : 1);
    for (std::size_t v = 0; v < m.num_vertices(); ++v) EXPECT_EQ(m.vertex_class(VertexId(v)).dim, d.dim == 3 ? 2 : 1);
    // Central points: the mean of the vertices, strictly inside (decided
    // exactly), for the volume cells other than the tet (whose circumcentre
    // lies outside this right-angled reference tet: clamped, not well-centred).
    const CentralPoint cp = cell_central_point(m, PrimalCellId(0u));
    if (d.dim == 3) EXPECT_EQ(cp.well_centred, t != CellType::Tet);
    if (t == CellType::Hex) EXPECT_EQ(cp.p, (Point3{0, 0, 0}));
    if (t == CellType::Quad) EXPECT_EQ(face_central_point(build_primal(one_cell(CellType::Hex)), PrimalFaceId(0u)).p.z == -1, true);
  }
}

TEST(PrimalMesh, MirroredTypeIsReorderedWithAWarning) {
  CellSoup s = one_cell(CellType::Prism);
  const CellDescriptor& d = descriptor(CellType::Prism);
  std::vector<std::uint32_t> v(6);
  for (int i = 0; i < 6; ++i) v[i] = std::uint32_t(d.mirror[i]);  // VTK's wedge order
  std::copy(v.begin(), v.end(), s.cell_vertex.begin());
  std::vector<std::string> warnings;
  const PrimalMesh m = build_primal(s, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("prisms are negatively oriented"), std::string::npos);
  EXPECT_EQ(walk(m), 5u);
}

namespace {

// A unit hexahedron, a pyramid on its x = 1 face (apex at x = 1.5) and a tet
// on each of the pyramid's four triangles: a tet + pyramid + hex block.
CellSoup hex_pyramid_tets() {
  CellSoup s;
  s.source = "<block>";
  s.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1},
              {1.5, 0.5, 0.5}, {1.5, -0.5, 0.5}, {1.5, 1.5, 0.5}, {1.5, 0.5, -0.5}, {1.5, 0.5, 1.5}};
  const std::uint32_t hex[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  s.add_cell(CellType::Hex, hex, 1);
  // Base loop (1, 2, 6, 5) runs into the hex: as the pyramid's (0, 3, 2, 1)
  // loop points out of the pyramid, base = (1, 5, 6, 2).
  const std::uint32_t pyr[5] = {1, 5, 6, 2, 8};
  s.add_cell(CellType::Pyramid, pyr, 2);
  // Tet on triangle (a, b, apex) of the pyramid, beyond it at point o.
  auto tet = [&](std::uint32_t a, std::uint32_t b, std::uint32_t o) {
    std::uint32_t t[4] = {a, b, 8, o};
    if (orient3d(s.points[a], s.points[b], s.points[8], s.points[o]) != Sign::Positive) std::swap(t[0], t[1]);
    s.add_cell(CellType::Tet, t, 3);
  };
  tet(1, 5, 9);
  tet(2, 6, 10);
  tet(1, 2, 11);
  tet(5, 6, 12);
  return s;
}

}  // namespace

TEST(PrimalMesh, TetPyramidHexBlock) {
  const PrimalMesh m = build_primal(hex_pyramid_tets());
  ASSERT_EQ(m.num_cells(), 6u);
  // Faces: 6 + 5 + 4*4 = 27 local faces, 5 shared (the quad, four triangles).
  EXPECT_EQ(m.num_faces(), 22u);
  EXPECT_EQ(walk(m), 17u);
  // The quad between hex and pyramid is shared whole, on the region interface.
  std::size_t quads = 0;
  for (std::size_t f = 0; f < m.num_faces(); ++f)
    if (m.face_vertices(PrimalFaceId(f)).size() == 4 && m.face_cell(PrimalFaceId(f), 1).valid()) {
      ++quads;
      EXPECT_EQ(m.face_class(PrimalFaceId(f)).dim, 2);
    }
  EXPECT_EQ(quads, 1u);
  // Around edge (1, 5): hex, pyramid and a tet, in one open chain of three.
  const auto chains = m.edge_chains(m.find_edge(VertexId(1u), VertexId(5u)));
  ASSERT_EQ(chains.size(), 1u);
  EXPECT_FALSE(chains[0].closed);
  std::vector<CellType> types;
  for (PrimalCellId c : chains[0].cells) types.push_back(m.cell_type(c));
  std::sort(types.begin(), types.end());
  EXPECT_EQ(types, (std::vector<CellType>{CellType::Tet, CellType::Pyramid, CellType::Hex}));
  // Vertex 1: on three cells' corner (hex, pyramid) and two tets.
  EXPECT_EQ(m.vertex_cells(VertexId(1u)).size(), 4u);
  // Around the apex's edge (1, 8): pyramid and the two tets on its triangles.
  EXPECT_EQ(m.edge_cells(m.find_edge(VertexId(1u), VertexId(8u))).size(), 3u);
}

TEST(PrimalMesh, PrismLayersOnTets) {
  // Two layers of prisms grown below the z = 0 face of a Kuhn lattice.
  const TetSoup lattice = kuhn_lattice(3, 3, 2);
  CellSoup s = cell_soup(lattice);
  const PrimalMesh tets = build_primal(s);
  const std::size_t n0 = s.points.size();
  std::vector<std::array<VertexId, 3>> floor;
  for (std::size_t f = 0; f < tets.num_faces(); ++f) {
    const auto fv = tets.face_vertices(PrimalFaceId(f));
    if (std::all_of(fv.begin(), fv.end(), [&](VertexId v) { return tets.point(v).z == 0; }))
      floor.push_back({fv[0], fv[1], fv[2]});
  }
  ASSERT_EQ(floor.size(), 18u);
  for (std::size_t i = 0; i < n0; ++i)
    if (s.points[i].z == 0) {
      s.points.push_back({s.points[i].x, s.points[i].y, -0.3});
      s.points.push_back({s.points[i].x, s.points[i].y, -0.5});
    }
  auto below = [&](VertexId v, int layer) {  // the copy of floor vertex v in a layer (1 or 2)
    std::uint32_t k = std::uint32_t(n0);
    for (std::size_t i = 0; i < v.idx; ++i) k += s.points[i].z == 0 ? 2 : 0;
    return k + std::uint32_t(layer - 1);
  };
  for (const auto& t : floor) {
    // The tet's loop (a, b, c) points down; the prism's top loop (3, 4, 5) must point up.
    const std::uint32_t a = t[0].idx, b = t[2].idx, c = t[1].idx;
    const std::uint32_t p1[6] = {below(t[0], 1), below(t[2], 1), below(t[1], 1), a, b, c};
    const std::uint32_t p2[6] = {below(t[0], 2), below(t[2], 2), below(t[1], 2), p1[0], p1[1], p1[2]};
    s.add_cell(CellType::Prism, p1, 7);
    s.add_cell(CellType::Prism, p2, 7);
  }
  const PrimalMesh m = build_primal(s);
  EXPECT_EQ(m.num_cells(), tets.num_cells() + 36);
  std::size_t local = 0;
  for (std::size_t c = 0; c < m.num_cells(); ++c) local += m.cell_descriptor(PrimalCellId(c)).num_faces;
  const std::size_t boundary = walk(m);
  EXPECT_EQ(local, 2 * m.num_faces() - boundary);
  // Interior edges have one closed chain; the triangles under the tets are now
  // interior and on the interface between regions 1 and 7.
  std::size_t closed = 0, interface_tris = 0;
  for (std::size_t e = 0; e < m.num_edges(); ++e) closed += m.edge_chains(EdgeId(e)).front().closed;
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    const auto fv = m.face_vertices(PrimalFaceId(f));
    if (fv.size() == 3 && m.face_cell(PrimalFaceId(f), 1).valid() &&
        std::all_of(fv.begin(), fv.end(), [&](VertexId v) { return m.point(v).z == 0; })) {
      ++interface_tris;
      EXPECT_EQ(m.face_class(PrimalFaceId(f)).dim, 2);
    }
  }
  EXPECT_EQ(interface_tris, 18u);
  EXPECT_GT(closed, 0u);
}

TEST(PrimalMesh, QuadAgainstTwoTrianglesIsANonConformalError) {
  CellSoup s;
  s.source = "nonconformal.msh";
  s.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, {2, 0.5, 0.5}};
  const std::uint32_t hex[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  s.add_cell(CellType::Hex, hex, 1, 11);
  // The hex's x = 1 face (1, 2, 6, 5) against triangles (1, 2, 6) and (1, 6, 5).
  for (auto t : {std::array<std::uint32_t, 4>{1, 2, 6, 8}, std::array<std::uint32_t, 4>{1, 6, 5, 8}}) {
    ASSERT_EQ(orient3d(s.points[t[0]], s.points[t[1]], s.points[t[2]], s.points[t[3]]), Sign::Positive);
    s.add_cell(CellType::Tet, t, 1, 12);
  }
  try {
    build_primal(s);
    FAIL() << "accepted a quadrangle against two triangles";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.source(), "nonconformal.msh");
    EXPECT_NE(what.find("non-conformal"), std::string::npos) << what;
    EXPECT_NE(what.find("hexahedron 1 (element 11)"), std::string::npos) << what;
    EXPECT_NE(what.find("tetrahedron"), std::string::npos) << what;
  }
}

TEST(PrimalMesh, TwistedAndOverlappingCellsAreErrorsNamingThem) {
  CellSoup s = one_cell(CellType::Hex);
  std::swap(s.cell_vertex[6], s.cell_vertex[7]);  // a twisted top face
  EXPECT_THROW(
      {
        try {
          build_primal(s);
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("hexahedron 1 is degenerate or twisted"), std::string::npos) << e.what();
          throw;
        }
      },
      InputError);
  CellSoup twice = one_cell(CellType::Tet);
  const std::uint32_t again[4] = {0, 1, 2, 3};
  twice.add_cell(CellType::Tet, again, 1);
  EXPECT_THROW(build_primal(twice), InputError);  // every face shared with the same orientation
}

// The packed tet mesh and the primal agree on random classified tet meshes:
// stars, faces, edges, chains (as cyclic sequences), model-face triangles.
TEST(PrimalMesh, AgreesWithClassifiedTetMeshOnRandomMeshes) {
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    RandomMeshParams p;
    p.seed = seed;
    p.num_points = 30 + int(seed % 30);
    p.regions = 1 + int(seed % 2);
    p.fracture = seed % 3 == 0;
    const TetSoup soup = random_classified_mesh(p);
    const ClassifiedTetMesh t = classify(soup);
    const PrimalMesh m = build_primal(cell_soup(soup));
    SCOPED_TRACE("seed " + std::to_string(seed));
    ASSERT_EQ(m.num_cells(), t.num_tets());
    ASSERT_EQ(m.num_faces(), t.num_triangles());
    ASSERT_EQ(m.num_edges(), t.num_edges());
    walk(m);
    auto pv = [&](VertexId v) { return VertexId(std::uint32_t(t.input_vertex(v))); };
    auto pc = [&](TetId x) { return PrimalCellId(t.input_tet(x)); };
    for (std::size_t v = 0; v < t.num_vertices(); ++v) {
      std::vector<PrimalCellId> star;
      for (TetId x : t.vertex_tets(VertexId(v))) star.push_back(pc(x));
      std::sort(star.begin(), star.end());
      const auto ms = m.vertex_cells(pv(VertexId(v)));
      EXPECT_EQ(star, std::vector<PrimalCellId>(ms.begin(), ms.end()));
    }
    for (std::size_t f = 0; f < t.num_triangles(); ++f) {
      const auto tv = t.triangle(TriId(f));
      const EdgeId e = m.find_edge(pv(tv[0]), pv(tv[1]));
      ASSERT_TRUE(e.valid());
      std::set<PrimalFaceId> found;  // the primal face on the same vertices, classified alike
      for (PrimalCellId c : m.edge_cells(e))
        for (int i = 0; i < 4; ++i) {
          const auto fv = m.face_vertices(m.cell_face(c, i));
          if (std::find(fv.begin(), fv.end(), pv(tv[2])) != fv.end() && std::find(fv.begin(), fv.end(), pv(tv[0])) != fv.end() &&
              std::find(fv.begin(), fv.end(), pv(tv[1])) != fv.end())
            found.insert(m.cell_face(c, i));
        }
      ASSERT_EQ(found.size(), 1u);
      const PrimalFaceId mf = *found.begin();
      EXPECT_EQ(m.face_class(mf).dim == 2, t.on_model_face(TriId(f)));
      std::set<PrimalCellId> tc{pc(t.triangle_tet(TriId(f), 0))}, mc{m.face_cell(mf, 0)};
      if (t.triangle_tet(TriId(f), 1).valid()) tc.insert(pc(t.triangle_tet(TriId(f), 1)));
      if (m.face_cell(mf, 1).valid()) mc.insert(m.face_cell(mf, 1));
      EXPECT_EQ(tc, mc);
    }
    std::vector<TetId> ring;
    std::vector<TriId> tris;
    for (std::size_t e = 0; e < t.num_edges(); ++e) {
      const auto [a, b] = t.edge(EdgeId(e));
      const EdgeId me = m.find_edge(pv(a), pv(b));
      ASSERT_TRUE(me.valid());
      const bool reversed = m.edge(me)[0] != pv(a);
      std::vector<std::vector<PrimalCellId>> tet_chains, primal_chains;
      t.for_each_edge_chain(EdgeId(e), ring, tris, [&](bool closed) {
        std::vector<PrimalCellId> ch;
        for (TetId x : ring) ch.push_back(pc(x));
        if (reversed) std::reverse(ch.begin(), ch.end());
        if (closed) std::rotate(ch.begin(), std::min_element(ch.begin(), ch.end()), ch.end());
        tet_chains.push_back(ch);
      });
      for (const EdgeChain& c : m.edge_chains(me)) {
        std::vector<PrimalCellId> ch = c.cells;
        if (c.closed) std::rotate(ch.begin(), std::min_element(ch.begin(), ch.end()), ch.end());
        primal_chains.push_back(ch);
      }
      std::sort(tet_chains.begin(), tet_chains.end());
      std::sort(primal_chains.begin(), primal_chains.end());
      EXPECT_EQ(tet_chains, primal_chains);
    }
  }
}

TEST(PrimalMesh, TaggedFaceOfNoCellIsAnErrorNamingIt) {
  CellSoup s = one_cell(CellType::Prism);
  s.points.push_back({5, 5, 5});
  s.faces.push_back({{0, 1, 6, 0}, 3, 4});  // a triangle through a point no cell has
  s.faces.push_back({{0, 1, 4, 3}, 4, 5});  // a real quadrangle of the prism
  try {
    build_primal(s);
    FAIL() << "accepted a tagged face of no cell";
  } catch (const InputError& e) {
    EXPECT_EQ(e.place(), "face (1 2 7)");
    EXPECT_NE(std::string(e.what()).find("tagged 4 is no face of any cell"), std::string::npos) << e.what();
  }
  s.faces.erase(s.faces.begin());
  const PrimalMesh m = build_primal(s);
  std::size_t tagged = 0;
  for (std::size_t f = 0; f < m.num_faces(); ++f) tagged += m.face_class(PrimalFaceId(f)) == ModelRef{2, 5};
  EXPECT_EQ(tagged, 1u);
}

// Two hexahedra touching along one edge only: the edge has two chains (the
// outside passes it twice), each one open hexahedron between boundary faces.
TEST(PrimalMesh, HexahedraTouchingAlongAnEdgeGiveTwoChains) {
  CellSoup s;
  s.source = "<touching>";
  for (double z : {0.0, 1.0})
    for (auto [x, y] : {std::pair{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}, {2.0, 1.0}, {2.0, 2.0}, {1.0, 2.0}})
      s.points.push_back({x, y, z});
  // Bottom layer: 0..6, top layer: 7..13; (1, 1) is vertex 2 / 9.
  const std::uint32_t a[8] = {0, 1, 2, 3, 7, 8, 9, 10}, b[8] = {2, 4, 5, 6, 9, 11, 12, 13};
  s.add_cell(CellType::Hex, a, 1);
  s.add_cell(CellType::Hex, b, 1);
  const PrimalMesh m = build_primal(s);
  walk(m);
  const EdgeId e = m.find_edge(VertexId(2u), VertexId(9u));
  ASSERT_TRUE(e.valid());
  EXPECT_EQ(m.edge_cells(e).size(), 2u);
  const auto chains = m.edge_chains(e);
  ASSERT_EQ(chains.size(), 2u);
  for (const EdgeChain& c : chains) {
    EXPECT_FALSE(c.closed);
    EXPECT_EQ(c.cells.size(), 1u);
  }
  EXPECT_NE(chains[0].cells[0], chains[1].cells[0]);
  EXPECT_EQ(m.edge_class(e).dim, 1);  // four boundary faces meet there: a model edge
}
