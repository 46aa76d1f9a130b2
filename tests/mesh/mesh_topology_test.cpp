// ClassifiedTetMesh adjacency invariants on random classified meshes:
// the face-adjacency involution, triangle/tet consistency, closed rings around
// interior edges and consistent stars.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>

#include "classify/classify.h"
#include "generate/random_mesh.h"
#include "predicates/predicates.h"

using namespace polydual;

TEST(MeshTopology, AdjacencyInvolutionRingsAndStars) {
  for (std::uint64_t seed = 1; seed <= 100; ++seed) {
    RandomMeshParams p;
    p.seed = seed;
    p.num_points = 40 + int(seed % 40);
    p.regions = 1 + int(seed % 2);
    p.fracture = seed % 3 == 0;
    p.lattice_points = seed % 5 == 0;
    ClassifiedTetMesh m = classify(random_classified_mesh(p));
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::size_t boundary_faces = 0;
    for (std::size_t t = 0; t < m.num_tets(); ++t) {
      for (int i = 0; i < 4; ++i) {
        const TetId s = m.tet_neighbor(TetId(t), i);
        const TriId f = m.tet_triangle(TetId(t), i);
        if (!s.valid()) {
          ++boundary_faces;
          EXPECT_FALSE(m.triangle_tet(f, 1).valid());
          continue;
        }
        // TT(TT(t,i), TTi(t,i)) == t, and both sides name the same triangle.
        int back = -1;
        for (int j = 0; j < 4; ++j)
          if (m.tet_neighbor(s, j) == TetId(t)) back = j;
        ASSERT_GE(back, 0);
        EXPECT_EQ(m.tet_triangle(s, back), f);
        // The shared triangle is the face opposite i (3 shared vertices).
        EXPECT_LT(m.local_index(s, m.tet(TetId(t))[i]), 0);
      }
    }
    // Triangles: oriented out of their first tet (exact orientation test).
    for (std::size_t f = 0; f < m.num_triangles(); ++f) {
      const auto& v = m.triangle(TriId(f));
      const TetId t0 = m.triangle_tet(TriId(f), 0);
      VertexId opp = VertexId::invalid();
      for (VertexId x : m.tet(t0))
        if (x != v[0] && x != v[1] && x != v[2]) opp = x;
      EXPECT_EQ(orient3d(m.point(v[0]), m.point(v[1]), m.point(v[2]), m.point(opp)), Sign::Negative);
    }
    // Euler-style count: 4 T = 2 F_interior + F_boundary.
    EXPECT_EQ(4 * m.num_tets(), 2 * m.num_triangles() - boundary_faces);
    // Rings: interior edges have closed rings; consecutive tets share the
    // triangle between them; every tet of the edge appears once.
    std::vector<TetId> ring;
    std::vector<TriId> tris;
    for (std::size_t e = 0; e < m.num_edges(); ++e) {
      bool closed;
      m.edge_ring(EdgeId(e), ring, tris, closed);
      const auto [a, b] = m.edge(EdgeId(e));
      std::size_t incident = 0;
      for (TetId t : m.vertex_tets(a)) incident += m.local_index(t, b) >= 0;
      EXPECT_EQ(ring.size(), incident);
      EXPECT_EQ(tris.size(), ring.size() + 1);
      if (closed) EXPECT_EQ(tris.front(), tris.back());
      bool on_boundary = false;
      for (TetId t : m.vertex_tets(a))
        for (int i = 0; i < 4; ++i)
          if (m.local_index(t, b) >= 0 && !m.tet_neighbor(t, i).valid() && m.tet(t)[i] != a && m.tet(t)[i] != b)
            on_boundary = true;
      EXPECT_EQ(closed, !on_boundary);
      for (std::size_t k = 0; k + 1 < ring.size(); ++k) {
        const TriId f = tris[k + 1];
        EXPECT_TRUE((m.triangle_tet(f, 0) == ring[k] && m.triangle_tet(f, 1) == ring[k + 1]) ||
                    (m.triangle_tet(f, 1) == ring[k] && m.triangle_tet(f, 0) == ring[k + 1]));
      }
    }
    // Stars: tet t is in the star of each of its four vertices exactly once.
    std::size_t star_total = 0;
    for (std::size_t v = 0; v < m.num_vertices(); ++v) {
      auto st = m.vertex_tets(VertexId(v));
      star_total += st.size();
      for (TetId t : st) EXPECT_GE(m.local_index(t, VertexId(v)), 0);
    }
    EXPECT_EQ(star_total, 4 * m.num_tets());
    if (HasFailure()) break;
  }
}

// classify() renumbers vertices and tets spatially (lib/classify/spatial_order.h):
// the maps back to the input are bijections and carry the same geometry and
// regions, and the new tet order follows the smallest vertex.
TEST(MeshTopology, SpatialRenumberingMapsBackToTheInput) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    RandomMeshParams p;
    p.seed = seed;
    p.num_points = 200;
    p.regions = 2;
    const TetSoup s = random_classified_mesh(p);
    const ClassifiedTetMesh m = classify(s);
    ASSERT_EQ(m.num_tets(), s.tets.size());
    std::set<std::uint32_t> seen_v, seen_t;
    for (std::size_t v = 0; v < m.num_vertices(); ++v) {
      const std::uint32_t in = m.input_vertex(VertexId(v));
      ASSERT_LT(in, s.points.size());
      EXPECT_TRUE(seen_v.insert(in).second);
      EXPECT_EQ(m.point(VertexId(v)), s.points[in]);
    }
    std::uint32_t prev_low = 0;
    bool identity = true;
    for (std::size_t t = 0; t < m.num_tets(); ++t) {
      const std::uint32_t in = m.input_tet(TetId(t));
      ASSERT_LT(in, s.tets.size());
      EXPECT_TRUE(seen_t.insert(in).second);
      identity = identity && in == t;
      EXPECT_EQ(m.region(TetId(t)), s.tet_region[in]);
      std::uint32_t low = UINT32_MAX;
      for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(m.input_vertex(m.tet(TetId(t))[i]), s.tets[in][i]) << "vertex order kept";
        low = std::min(low, m.tet(TetId(t))[i].idx);
      }
      EXPECT_GE(low, prev_low) << "tets sorted by smallest vertex";
      prev_low = low;
    }
    EXPECT_FALSE(identity) << "seed " << seed << ": Delaunay output is not already in Morton order";
  }
}

// Edges are numbered by (lower vertex, higher vertex) and every tet names its
// six edges, also around a vertex with very many neighbours (build_topology
// counts ranks for a few neighbours and sorts for many): a bipyramid fan of
// n tets around the axis (apex, bottom), whose two poles have n + 1 neighbours.
TEST(MeshTopology, EdgeNumberingAroundHighValenceVertices) {
  for (int n : {5, 40, 150}) {
    SCOPED_TRACE("fan of " + std::to_string(n));
    TetSoup s;
    s.source = "fan";
    s.points.push_back({0, 0, 1});
    s.points.push_back({0, 0, -1});
    for (int i = 0; i < n; ++i) {
      const double a = 2 * 3.14159265358979 * i / n;
      s.points.push_back({std::cos(a), std::sin(a), 0.0});
    }
    for (int i = 0; i < n; ++i) {
      std::array<std::uint32_t, 4> t{0, 1, std::uint32_t(2 + i), std::uint32_t(2 + (i + 1) % n)};
      if (orient3d(s.points[t[0]], s.points[t[1]], s.points[t[2]], s.points[t[3]]) != Sign::Positive)
        std::swap(t[2], t[3]);
      s.tets.push_back(t);
      s.tet_region.push_back(1);
    }
    const ClassifiedTetMesh m = classify(s);
    ASSERT_EQ(m.num_edges(), std::size_t(1 + 3 * n));  // the axis, n spokes per pole, n rim edges
    for (std::size_t e = 0; e < m.num_edges(); ++e) {
      const auto [a, b] = m.edge(EdgeId(e));
      EXPECT_LT(a, b);
      if (e > 0) {
        const auto [pa, pb] = m.edge(EdgeId(e - 1));
        EXPECT_TRUE(pa < a || (pa == a && pb < b)) << "edge " << e << " out of (a, b) order";
      }
      EXPECT_GE(m.local_index(m.edge_tet(EdgeId(e)), a), 0);
      EXPECT_GE(m.local_index(m.edge_tet(EdgeId(e)), b), 0);
      EXPECT_EQ(m.find_edge(a, b), EdgeId(e));
      EXPECT_EQ(m.find_edge(b, a), EdgeId(e));
    }
    for (std::size_t t = 0; t < m.num_tets(); ++t)
      for (int k = 0; k < 6; ++k) {
        const auto [a, b] = m.edge(m.tet_edge(TetId(t), k));
        const VertexId p = m.tet(TetId(t))[kTetEdge[k][0]], q = m.tet(TetId(t))[kTetEdge[k][1]];
        EXPECT_EQ(std::min(p, q), a);
        EXPECT_EQ(std::max(p, q), b);
      }
  }
}

namespace {

// Checks the chains of every edge of m (proofs/edge_chains.md E1): each tet
// around the edge in exactly one chain; consecutive tets of a chain sharing
// the triangle between them; an open chain running from a boundary triangle
// to a boundary triangle; several chains exactly for the listed edges, and
// then one per two boundary triangles at the edge. Returns the number of
// edges with several chains.
std::size_t check_edge_chains(const ClassifiedTetMesh& m) {
  std::vector<TetId> ring;
  std::vector<TriId> tris;
  std::size_t several = 0;
  for (std::size_t e = 0; e < m.num_edges(); ++e) {
    const EdgeId eid(e);
    const auto [a, b] = m.edge(eid);
    std::multiset<std::uint32_t> around, chained;
    std::size_t boundary = 0;
    for (TetId t : m.vertex_tets(a)) {
      if (m.local_index(t, b) < 0) continue;
      around.insert(t.idx);
      for (int i = 0; i < 4; ++i)
        boundary += m.tet(t)[i] != a && m.tet(t)[i] != b && !m.tet_neighbor(t, i).valid();
    }
    std::size_t chains = 0;
    m.for_each_edge_chain(eid, ring, tris, [&](bool closed) {
      ++chains;
      EXPECT_EQ(tris.size(), ring.size() + 1);
      for (TetId t : ring) chained.insert(t.idx);
      for (std::size_t k = 0; k + 1 < ring.size(); ++k) {
        const TriId f = tris[k + 1];
        EXPECT_TRUE((m.triangle_tet(f, 0) == ring[k] && m.triangle_tet(f, 1) == ring[k + 1]) ||
                    (m.triangle_tet(f, 1) == ring[k] && m.triangle_tet(f, 0) == ring[k + 1]));
      }
      if (closed) EXPECT_EQ(tris.front(), tris.back());
      else EXPECT_TRUE(!m.triangle_tet(tris.front(), 1).valid() && !m.triangle_tet(tris.back(), 1).valid());
    });
    EXPECT_EQ(chained, around) << "edge " << e;
    EXPECT_EQ(m.has_several_chains(eid), chains > 1) << "edge " << e;
    if (boundary > 0) EXPECT_EQ(2 * chains, boundary) << "edge " << e;
    several += chains > 1;
  }
  EXPECT_EQ(several, m.multi_chain_edges().size());
  return several;
}

}  // namespace

// The chains on the touching family (random_mesh.h: two blocks of different
// materials touching along edges between two wedges of outside, on a slab of
// a third) and on fans of n tets around one axis with every other tet left
// out (n / 2 chains of one tet around the axis).
TEST(MeshTopology, EdgeChainsPartitionTheTetsAroundEachEdge) {
  std::size_t touching_meshes = 0;
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    RandomMeshParams p;
    p.seed = seed;
    p.num_points = 40 + int(seed % 50);
    p.touching = true;
    SCOPED_TRACE("touching seed " + std::to_string(seed));
    touching_meshes += check_edge_chains(classify(random_classified_mesh(p))) > 0;
    if (HasFailure()) break;
  }
  EXPECT_GE(touching_meshes, 55u) << "the family must touch itself along edges in most meshes";
  std::printf("touching meshes with edges of several chains: %zu of 60\n", touching_meshes);
  for (int n : {4, 6, 12}) {
    SCOPED_TRACE("fan of " + std::to_string(n) + " with gaps");
    TetSoup s;
    s.source = "fan with gaps";
    s.points = {{0, 0, -1}, {0, 0, 1}};
    for (int i = 0; i < n; ++i)
      s.points.push_back({std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n), 0});
    for (int i = 0; i < n; i += 2) {
      std::array<std::uint32_t, 4> t{0, 1, std::uint32_t(2 + i), std::uint32_t(2 + (i + 1) % n)};
      if (orient3d(s.points[t[0]], s.points[t[1]], s.points[t[2]], s.points[t[3]]) != Sign::Positive)
        std::swap(t[2], t[3]);
      s.tets.push_back(t);
      s.tet_region.push_back(1 + i % 3);
    }
    const ClassifiedTetMesh m = classify(s);
    EXPECT_EQ(check_edge_chains(m), 1u);
    const EdgeId axis = m.multi_chain_edges()[0];
    EXPECT_EQ(m.input_vertex(m.edge(axis)[0]) + m.input_vertex(m.edge(axis)[1]), 1u) << "the axis (0, 1)";
    std::vector<TetId> ring;
    std::vector<TriId> tris;
    int chains = 0;
    m.for_each_edge_chain(axis, ring, tris, [&](bool) { ++chains; });
    EXPECT_EQ(chains, n / 2);
  }
}
