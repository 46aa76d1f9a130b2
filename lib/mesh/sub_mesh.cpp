#include "mesh/sub_mesh.h"

#include <algorithm>
#include <stdexcept>

namespace polydual {

std::vector<TetId> star_tets(const ClassifiedTetMesh& m, std::span<const VertexId> vertices) {
  std::vector<char> in(m.num_tets(), 0);  // a mark per tet, then one ordered pass: no sort
  for (VertexId v : vertices)
    for (TetId t : m.vertex_tets(v)) in[t.idx] = 1;
  std::vector<TetId> out;
  for (std::size_t t = 0; t < in.size(); ++t)
    if (in[t]) out.push_back(TetId(t));
  return out;
}

SubMesh sub_mesh(const ClassifiedTetMesh& m, std::span<const TetId> tets) {
  for (std::size_t i = 0; i < tets.size(); ++i)
    if (tets[i].idx >= m.num_tets() || (i > 0 && tets[i - 1].idx >= tets[i].idx))
      throw std::invalid_argument("sub_mesh: tets not increasing or out of range at position " + std::to_string(i));
  SubMesh s;
  std::vector<std::uint32_t> local(m.num_vertices(), std::uint32_t(-1));
  for (TetId t : tets)
    for (VertexId v : m.tet(t)) local[v.idx] = 0;
  std::vector<Point3> points;
  std::vector<std::uint32_t> input_vertex;
  for (std::size_t v = 0; v < local.size(); ++v) {
    if (local[v] != 0) continue;
    local[v] = std::uint32_t(s.vertex.size());
    s.vertex.push_back(VertexId(v));
    points.push_back(m.point(VertexId(v)));
    input_vertex.push_back(m.input_vertex(VertexId(v)));
  }
  std::vector<std::array<VertexId, 4>> sub_tets;
  std::vector<std::int32_t> regions;
  std::vector<std::uint32_t> input_tet;
  sub_tets.reserve(tets.size());
  for (TetId t : tets) {
    const auto& q = m.tet(t);
    sub_tets.push_back({VertexId(local[q[0].idx]), VertexId(local[q[1].idx]), VertexId(local[q[2].idx]),
                        VertexId(local[q[3].idx])});
    regions.push_back(m.region(t));
    input_tet.push_back(m.input_tet(t));
  }
  s.tet.assign(tets.begin(), tets.end());
  s.mesh = TetMeshBuilder::build_topology(m.source(), std::move(points), std::move(sub_tets), std::move(regions),
                                          std::move(input_vertex), std::move(input_tet));
  ClassifiedTetMesh& sm = s.mesh;
  auto& vc = TetMeshBuilder::vertex_class(sm);
  vc.resize(sm.num_vertices());
  for (std::size_t v = 0; v < vc.size(); ++v) vc[v] = m.vertex_class(s.vertex[v]);
  // Same vertex order in every tet: local face i and local edge k of a
  // sub-mesh tet are those of its whole-mesh tet.
  auto& tf = TetMeshBuilder::triangle_face(sm);
  tf.assign(sm.num_triangles(), TetMeshBuilder::kNoFace);
  auto& ec = TetMeshBuilder::edge_class(sm);
  ec.assign(sm.num_edges(), ModelRef{});
  for (std::size_t t = 0; t < tets.size(); ++t) {
    const TetId st(t), wt = tets[t];
    for (int i = 0; i < 4; ++i) {
      const TriId f = m.tet_triangle(wt, i);
      if (m.on_model_face(f)) tf[sm.tet_triangle(st, i).idx] = m.triangle_class(f).tag;
    }
    for (int k = 0; k < 6; ++k) ec[sm.tet_edge(st, k).idx] = m.edge_class(m.tet_edge(wt, k));
  }
  TetMeshBuilder::model(sm) = m.model();
  TetMeshBuilder::classification_warnings(sm) = m.classification_warnings();
  return s;
}

}  // namespace polydual
