// The classified structure of a tet mesh as comparable sets, shared by the
// tests of the tet stage's topological passes (flips, interior points), which
// must keep it exactly.
#pragma once
#include <algorithm>
#include <cstdint>
#include <set>
#include <tuple>

#include "mesh/classified_tet_mesh.h"

namespace polydual::testing {

using TriKey = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::int32_t>;
using EdgeKey = std::tuple<std::uint32_t, std::uint32_t, int, std::int32_t>;

// Model-face triangles as (sorted vertices, tag).
inline std::set<TriKey> model_face_triangles(const ClassifiedTetMesh& m) {
  std::set<TriKey> s;
  for (std::size_t f = 0; f < m.num_triangles(); ++f) {
    if (!m.on_model_face(TriId(f))) continue;
    auto v = m.triangle(TriId(f));
    std::sort(v.begin(), v.end());
    s.insert({v[0].idx, v[1].idx, v[2].idx, m.triangle_class(TriId(f)).tag});
  }
  return s;
}

// Edges on a model edge or face as (vertices, dim, tag).
inline std::set<EdgeKey> constrained_edges(const ClassifiedTetMesh& m) {
  std::set<EdgeKey> s;
  for (std::size_t e = 0; e < m.num_edges(); ++e) {
    const ModelRef r = m.edge_class(EdgeId(e));
    if (r.dim >= 3) continue;
    const auto [a, b] = m.edge(EdgeId(e));
    s.insert({a.idx, b.idx, r.dim, r.tag});
  }
  return s;
}

}  // namespace polydual::testing
