#include "mesh/model_facets.h"

namespace polydual {

ModelFacets model_facets(const ClassifiedTetMesh& m) {
  ModelFacets f;
  f.points = m.points();
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    const ModelRef r = m.triangle_class(TriId(t));
    if (r.dim == 2) f.triangles.push_back({m.triangle(TriId(t)), r.tag, static_cast<std::uint32_t>(t)});
  }
  for (std::size_t e = 0; e < m.num_edges(); ++e) {
    const ModelRef r = m.edge_class(EdgeId(e));
    if (r.dim != 1 && r.dim != 2) continue;
    const auto& ev = m.edge(EdgeId(e));
    const ModelFacet s{{ev[0], ev[1], VertexId::invalid()}, r.tag, static_cast<std::uint32_t>(e)};
    (r.dim == 1 ? f.segments : f.face_edges).push_back(s);
  }
  return f;
}

ModelFacets model_facets(const PrimalMesh& m) {
  ModelFacets f;
  f.points = m.points();
  if (m.dim() == 3)
    for (std::size_t i = 0; i < m.num_faces(); ++i) {
      const ModelRef r = m.face_class(PrimalFaceId(i));
      if (r.dim != 2) continue;
      const auto v = m.face_vertices(PrimalFaceId(i));
      const std::uint32_t src = static_cast<std::uint32_t>(i);
      f.triangles.push_back({{v[0], v[1], v[2]}, r.tag, src});
      if (v.size() == 4) f.triangles.push_back({{v[0], v[2], v[3]}, r.tag, src});
    }
  for (std::size_t e = 0; e < m.num_edges(); ++e) {
    const ModelRef r = m.edge_class(EdgeId(e));
    if (r.dim != 1 && r.dim != 2) continue;
    const auto ev = m.edge(EdgeId(e));
    const ModelFacet s{{ev[0], ev[1], VertexId::invalid()}, r.tag, static_cast<std::uint32_t>(e)};
    (r.dim == 1 ? f.segments : f.face_edges).push_back(s);
  }
  return f;
}

}  // namespace polydual
