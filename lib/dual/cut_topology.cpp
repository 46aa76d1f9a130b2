#include "dual/cut_topology.h"

#include <algorithm>
#include <string>

#include "core/error.h"

namespace polydual {

namespace {

void check_cuts(const ClassifiedTetMesh& m, const VertexCuts& c) {
  const std::string src = m.source();
  const std::size_t nv = m.num_vertices();
  if (c.off.size() != nv + 1)
    throw InputError(src, "vertex cuts", "offsets for " + std::to_string(c.off.size()) + " entries, the mesh has " +
                                             std::to_string(nv) + " vertices (needs vertices + 1)");
  if (!c.whole.empty() && c.whole.size() != nv)
    throw InputError(src, "vertex cuts", "whole flags for " + std::to_string(c.whole.size()) + " vertices, the mesh has " +
                                             std::to_string(nv));
  if (c.off[0] != 0 || c.off[nv] != c.tri.size())
    throw InputError(src, "vertex cuts", "offsets do not span the triangle list");
  for (std::size_t v = 0; v < nv; ++v) {
    const std::string place = "vertex cuts of vertex " + std::to_string(m.input_vertex(VertexId(v)));
    if (c.off[v + 1] < c.off[v]) throw InputError(src, place, "offsets decrease");
    for (std::uint32_t k = c.off[v]; k < c.off[v + 1]; ++k) {
      const TriId f = c.tri[k];
      const std::string at = place + ", triangle " + std::to_string(f.idx);
      if (f.idx >= m.num_triangles()) throw InputError(src, at, "no such triangle");
      if (k > c.off[v] && !(c.tri[k - 1].idx < f.idx)) throw InputError(src, at, "triangles not increasing");
      const auto t = m.triangle(f);
      if (std::find(t.begin(), t.end(), VertexId(v)) == t.end())
        throw InputError(src, at, "the triangle does not contain the vertex");
      if (m.on_model_face(f)) throw InputError(src, at, "the triangle is on a model face (a cut must be virtual)");
    }
  }
}

// Whether edge e is a stop edge, and whether a cap of each end ends on it
// (|C_a(e)| > 0, |C_b(e)| > 0). C_x(e) = (M ∪ cut(x)) ∩ T(e), P = C_a ∪ C_b.
// Not a stop edge iff |P| ∈ {0, 2} and each of C_a, C_b is empty or P: only
// then does every cell at a and at b meet the midpoint in exactly two faces
// (proofs/dual_cuts.md, rule S), so that it can be left out.
struct EdgeStop { bool stop, caps_a, caps_b; };

EdgeStop edge_stop(const ClassifiedTetMesh& m, const CutTopology& ct, EdgeId e, std::vector<TetId>& ring,
                   std::vector<TriId>& tris) {
  const auto [a, b] = m.edge(e);
  bool closed;
  m.edge_ring(e, ring, tris, closed);
  const std::size_t nk = closed ? ring.size() : ring.size() + 1;
  std::size_t p = 0, ca = 0, cb = 0;
  for (std::size_t k = 0; k < nk; ++k) {
    const bool mf = m.on_model_face(tris[k]);
    const bool in_a = mf || ct.cut_by(tris[k], a), in_b = mf || ct.cut_by(tris[k], b);
    p += in_a || in_b;
    ca += in_a;
    cb += in_b;
  }
  const bool keep = (p == 0 || p == 2) && (ca == 0 || ca == p) && (cb == 0 || cb == p);
  return {m.edge_class(e).dim == 1 || !keep, ca > 0, cb > 0};
}

}  // namespace

bool pinned(const ClassifiedTetMesh& m, const VertexCuts* cuts, PointOrigin o) {
  if (cuts == nullptr || cuts->whole.empty() || o.dim < 0) return false;
  auto any = [&](const auto& vs) {
    return std::any_of(vs.begin(), vs.end(), [&](VertexId v) { return cuts->is_whole(v); });
  };
  switch (o.dim) {
    case 0: return cuts->is_whole(VertexId(o.id));
    case 1: return any(m.edge(EdgeId(o.id)));
    case 2: return any(m.triangle(TriId(o.id)));
    default: return any(m.tet(TetId(o.id)));
  }
}

Point3 barycentre(const ClassifiedTetMesh& m, PointOrigin o) {
  switch (o.dim) {
    case 0: return m.point(VertexId(o.id));
    case 1: {
      const auto v = m.edge(EdgeId(o.id));
      return 0.5 * (m.point(v[0]) + m.point(v[1]));
    }
    case 2: {
      const auto v = m.triangle(TriId(o.id));
      const Point3& a = m.point(v[0]);
      return a + (m.point(v[1]) - a) / 3.0 + (m.point(v[2]) - a) / 3.0;
    }
    default: {
      const auto v = m.tet(TetId(o.id));
      return 0.25 * (m.point(v[0]) + m.point(v[1]) + m.point(v[2]) + m.point(v[3]));
    }
  }
}

CutTopology cut_topology(const ClassifiedTetMesh& m, const VertexCuts* cuts) {
  CutTopology ct;
  if (cuts == nullptr || cuts->empty()) return ct;
  check_cuts(m, *cuts);
  ct.active = true;
  ct.cuts = cuts;
  ct.tri_mask.assign(m.num_triangles(), 0);
  for (std::size_t v = 0; v < m.num_vertices(); ++v)
    for (TriId f : cuts->of(VertexId(v))) {
      const auto t = m.triangle(f);
      for (int i = 0; i < 3; ++i)
        if (t[i] == VertexId(v)) ct.tri_mask[f.idx] |= std::uint8_t(1u << i);
    }
  // The edges of every cut triangle have a cut in their ring.
  ct.edge_bits.assign(m.num_edges(), 0);
  for (std::size_t f = 0; f < ct.tri_mask.size(); ++f) {
    if (ct.tri_mask[f] == 0) continue;
    const auto t = m.triangle(TriId(f));
    for (int i = 0; i < 3; ++i)
      ct.edge_bits[m.triangle_edge(TriId(f), t[i], t[(i + 1) % 3]).idx] |= CutTopology::kRingCut;
  }
  // Stop edges; per vertex the number of stop edges on which one of its caps
  // ends (saturating at 3: only ">= 3" matters).
  std::vector<std::uint8_t> ends(m.num_vertices(), 0);
  std::vector<TetId> ring;
  std::vector<TriId> tris;
  for (std::size_t ei = 0; ei < m.num_edges(); ++ei) {
    const EdgeId e(ei);
    const auto [a, b] = m.edge(e);
    const bool model_edge = m.edge_class(e).dim == 1;
    const bool whole = cuts->is_whole(a) || cuts->is_whole(b);
    if (!model_edge && !whole && cuts->of(a).empty() && cuts->of(b).empty()) continue;
    EdgeStop s = edge_stop(m, ct, e, ring, tris);
    s.stop = s.stop || whole;  // C5: every edge of a whole vertex has its midpoint
    if (!s.stop) continue;
    ct.edge_bits[ei] |= CutTopology::kStop;
    if (s.caps_a && ends[a.idx] < 3) ++ends[a.idx];
    if (s.caps_b && ends[b.idx] < 3) ++ends[b.idx];
  }
  ct.vertex_point.assign(m.num_vertices(), 0);
  for (std::size_t v = 0; v < m.num_vertices(); ++v)
    ct.vertex_point[v] = char(m.vertex_class(VertexId(v)).dim == 0 || ends[v] >= 3);
  return ct;
}

}  // namespace polydual
