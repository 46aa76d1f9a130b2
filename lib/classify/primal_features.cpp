#include "classify/primal_features.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "classify/features.h"
#include "core/union_find.h"

namespace polydual {

namespace {

// Unit Newell normal of a face loop (a quadrangle's mean plane).
Vec3 loop_normal(const PrimalMesh& m, std::span<const VertexId> v) {
  Vec3 n{0, 0, 0};
  for (std::size_t k = 0; k < v.size(); ++k) n = n + cross(m.point(v[k]), m.point(v[(k + 1) % v.size()]));
  const double l = norm(n);
  return l > 0 ? n * (1.0 / l) : n;
}

// Whether face f's loop runs a -> b.
bool runs(std::span<const VertexId> v, VertexId a, VertexId b) {
  for (std::size_t k = 0; k < v.size(); ++k)
    if (v[k] == a && v[(k + 1) % v.size()] == b) return true;
  return false;
}

// The edges inside inferred model faces (class dim 2) with their two faces.
struct InnerEdge {
  EdgeId e;
  PrimalFaceId f[2];
};

std::vector<InnerEdge> inner_edges(const PrimalMesh& m, const std::vector<char>& inferred) {
  std::vector<InnerEdge> out;
  std::vector<std::uint32_t> slot(m.num_edges(), ~0u);
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    if (!inferred[f]) continue;
    const auto v = m.face_vertices(PrimalFaceId(f));
    for (std::size_t k = 0; k < v.size(); ++k) {
      const EdgeId e = m.find_edge(v[k], v[(k + 1) % v.size()]);
      if (m.edge_class(e).dim != 2) continue;
      if (slot[e.idx] == ~0u) {
        slot[e.idx] = std::uint32_t(out.size());
        out.push_back({e, {PrimalFaceId(f), PrimalFaceId::invalid()}});
      } else {
        out[slot[e.idx]].f[1] = PrimalFaceId(f);
      }
    }
  }
  std::erase_if(out, [](const InnerEdge& x) { return !x.f[1].valid(); });
  return out;
}

// The bend of an inner edge, normals oriented out of the sheet's smaller
// region (a boundary face's loop already points out of its one cell).
BendEdge bend_of(const PrimalMesh& m, const InnerEdge& x) {
  auto oriented = [&](PrimalFaceId f, bool& flip) {
    const PrimalCellId c0 = m.face_cell(f, 0), c1 = m.face_cell(f, 1);
    flip = c1.valid() && m.cell_class(c1).tag < m.cell_class(c0).tag;
    const Vec3 n = loop_normal(m, m.face_vertices(f));
    return flip ? n * -1.0 : n;
  };
  const auto [a, b] = m.edge(x.e);
  BendEdge be;
  be.a = a.idx;
  be.b = b.idx;
  be.dir = m.point(b) - m.point(a);
  bool flip0 = false, flip1 = false;
  const Vec3 n0 = oriented(x.f[0], flip0), n1 = oriented(x.f[1], flip1);
  const bool left0 = runs(m.face_vertices(x.f[0]), a, b) != flip0;
  const bool left1 = runs(m.face_vertices(x.f[1]), a, b) != flip1;
  be.bend = angle_deg(n0, n1);
  if (left0 != left1) {
    be.left = left0 ? n0 : n1;
    be.right = left0 ? n1 : n0;
  }
  return be;
}

}  // namespace

std::size_t tag_inferred_model_faces(CellSoup& soup, const PrimalMesh& m, double feature_angle_deg) {
  if (m.dim() != 3) return 0;
  std::set<std::int32_t> given;
  std::int32_t next = 0;
  for (const TaggedPolygon& p : soup.faces) given.insert(p.tag), next = std::max(next, p.tag);
  std::vector<char> inferred(m.num_faces(), 0);
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    const ModelRef r = m.face_class(PrimalFaceId(f));
    if (r.dim != 2) continue;
    next = std::max(next, r.tag);
    inferred[f] = char(!given.count(r.tag));
  }
  const std::vector<InnerEdge> edges = inner_edges(m, inferred);
  std::vector<BendEdge> bends;
  for (const InnerEdge& x : edges) bends.push_back(bend_of(m, x));
  FeatureRule rule;
  rule.feature_deg = feature_angle_deg;
  rule.strong_deg = std::max(rule.strong_deg, feature_angle_deg);
  const std::vector<FeatureVerdict> verdict = select_feature_edges(bends, rule);
  UnionFind parts(m.num_faces());
  for (std::size_t k = 0; k < edges.size(); ++k)
    if (verdict[k] != FeatureVerdict::Strong && verdict[k] != FeatureVerdict::Chain)
      parts.unite(edges[k].f[0].idx, edges[k].f[1].idx);
  std::vector<std::int32_t> tag_of(m.num_faces(), 0);
  std::size_t count = 0;
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    if (!inferred[f]) continue;
    const std::uint32_t root = parts.find(f);  // the part's smallest face: numbered by first face
    if (root == f) tag_of[f] = ++next, ++count;
    else tag_of[f] = tag_of[root];
    const auto v = m.face_vertices(PrimalFaceId(f));
    TaggedPolygon p;
    p.n = std::uint8_t(v.size());
    for (std::size_t k = 0; k < v.size(); ++k) p.v[k] = std::uint32_t(m.input_vertex(v[k]));
    p.tag = tag_of[f];
    soup.faces.push_back(p);
  }
  return count;
}

}  // namespace polydual
