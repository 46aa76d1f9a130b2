#include "dual/cut_topology.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <atomic>
#include <string>

#include "core/error.h"

namespace polydual {

namespace {

// The first problem of vertex v's cut set (null: none); `at` is then the
// position in c.tri of the triangle it is about, or c.tri.size() + 1 when it
// is about the offsets.
const char* vertex_cut_problem(const ClassifiedTetMesh& m, const VertexCuts& c, std::size_t v, std::size_t& at) {
  at = c.tri.size() + 1;
  if (c.off[v + 1] < c.off[v]) return "offsets decrease";
  if (c.off[v + 1] > c.tri.size()) return "offsets past the triangle list";
  for (std::uint32_t k = c.off[v]; k < c.off[v + 1]; ++k) {
    at = k;
    const TriId f = c.tri[k];
    if (f.idx >= m.num_triangles()) return "no such triangle";
    if (k > c.off[v] && !(c.tri[k - 1].idx < f.idx)) return "triangles not increasing";
    const auto t = m.triangle(f);
    if (std::find(t.begin(), t.end(), VertexId(std::uint32_t(v))) == t.end())
      return "the triangle does not contain the vertex";
    if (m.on_model_face(f)) return "the triangle is on a model face (a cut must be virtual)";
  }
  return nullptr;
}

// The vertices are checked in parallel; the error thrown is the one of the
// first bad vertex (the same for any thread count, and as a serial walk).
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
  const std::size_t first_bad = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, nv, 4096), nv,
      [&](const tbb::blocked_range<std::size_t>& r, std::size_t best) {
        std::size_t at;
        for (std::size_t v = r.begin(); v < r.end() && v < best; ++v)
          if (vertex_cut_problem(m, c, v, at)) return v;
        return best;
      },
      [](std::size_t x, std::size_t y) { return std::min(x, y); });
  if (first_bad == nv) return;
  std::size_t at;
  const char* what = vertex_cut_problem(m, c, first_bad, at);
  std::string place = "vertex cuts of vertex " + std::to_string(m.input_vertex(VertexId(std::uint32_t(first_bad))));
  if (at < c.tri.size()) place += ", triangle " + std::to_string(c.tri[at].idx);
  throw InputError(src, place, what);
}

// Whether edge e is a stop edge, and whether a cap of each end ends on it
// (|C_a(e)| > 0, |C_b(e)| > 0). C_x(e) = (M ∪ cut(x)) ∩ T(e), P = C_a ∪ C_b.
// Not a stop edge iff |P| ∈ {0, 2} and each of C_a, C_b is empty or P: only
// then does every cell at a and at b meet the midpoint in exactly two faces
// (proofs/dual_cuts.md, rule S), so that it can be left out. T(e) holds the
// triangles of every chain of e (proofs/edge_chains.md; an edge with several
// chains has boundary triangles in each, so it is a model edge anyway).
struct EdgeStop { bool stop, caps_a, caps_b; };

EdgeStop edge_stop(const ClassifiedTetMesh& m, const CutTopology& ct, EdgeId e, std::vector<TetId>& ring,
                   std::vector<TriId>& tris) {
  const VertexId a = m.edge(e)[0], b = m.edge(e)[1];  // not a structured binding: the lambda captures them
  std::size_t p = 0, ca = 0, cb = 0;
  m.for_each_edge_chain(e, ring, tris, [&](bool closed) {
    const std::size_t nk = closed ? ring.size() : ring.size() + 1;
    for (std::size_t k = 0; k < nk; ++k) {
      const bool mf = m.on_model_face(tris[k]);
      const bool in_a = mf || ct.position_for(m, tris[k], a), in_b = mf || ct.position_for(m, tris[k], b);
      p += in_a || in_b;
      ca += in_a;
      cb += in_b;
    }
  });
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
  // Each phase in parallel; the bits are set by atomic ORs, so the masks are
  // the same for any thread count and order.
  ct.tri_mask.assign(m.num_triangles(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m.num_vertices(), 4096), [&](const auto& r) {
    for (std::size_t v = r.begin(); v < r.end(); ++v)
      for (TriId f : cuts->of(VertexId(v))) {
        const auto t = m.triangle(f);
        for (int i = 0; i < 3; ++i)
          if (t[i] == VertexId(v)) std::atomic_ref<std::uint8_t>(ct.tri_mask[f.idx]).fetch_or(std::uint8_t(1u << i), std::memory_order_relaxed);
      }
  });
  // Every interior triangle through a whole vertex keeps its centre (bit
  // kCentre: is_cut, but cut by none of its vertices unless its bit says
  // so): the cells of a whole vertex are then unions of its barycentric
  // corners, and its neighbours' cells do not depend on which of its
  // triangles cut it (split/coarsen.h; proofs/dual_cuts.md C5). With every
  // interior triangle cut (the fallback) the bit changes nothing.
  if (cuts->any_whole())
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m.num_vertices(), 4096), [&](const auto& r) {
      for (std::size_t v = r.begin(); v < r.end(); ++v) {
        if (!cuts->is_whole(VertexId(v))) continue;
        for (TetId t : m.vertex_tets(VertexId(v)))
          for (int i = 0; i < 4; ++i) {
            if (m.tet(t)[i] == VertexId(v)) continue;
            const TriId f = m.tet_triangle(t, i);
            if (!m.on_model_face(f))
              std::atomic_ref<std::uint8_t>(ct.tri_mask[f.idx]).fetch_or(CutTopology::kCentre, std::memory_order_relaxed);
          }
      }
    });
  // The edges of every cut triangle have a cut in their ring.
  ct.edge_bits.assign(m.num_edges(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ct.tri_mask.size(), 16384), [&](const auto& r) {
    for (std::size_t f = r.begin(); f < r.end(); ++f) {
      if (ct.tri_mask[f] == 0) continue;
      const auto t = m.triangle(TriId(f));
      for (int i = 0; i < 3; ++i)
        std::atomic_ref<std::uint8_t>(ct.edge_bits[m.triangle_edge(TriId(f), t[i], t[(i + 1) % 3]).idx])
            .fetch_or(CutTopology::kRingCut, std::memory_order_relaxed);
    }
  });
  // Stop edges (each edge writes its own bits), with two passing bits: a cap
  // of end a (kCapsA), of end b (kCapsB) ends on it. Then, serially, per
  // vertex the number of stop edges on which one of its caps ends
  // (saturating at 3: only ">= 3" matters), clearing the passing bits.
  constexpr std::uint8_t kCapsA = 4, kCapsB = 8;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m.num_edges(), 8192), [&](const auto& r) {
    std::vector<TetId> ring;
    std::vector<TriId> tris;
    for (std::size_t ei = r.begin(); ei < r.end(); ++ei) {
      const EdgeId e(ei);
      const auto [a, b] = m.edge(e);
      const bool model_edge = m.edge_class(e).dim == 1;
      const bool whole = cuts->is_whole(a) || cuts->is_whole(b);
      if (!model_edge && !whole && cuts->of(a).empty() && cuts->of(b).empty()) continue;
      EdgeStop s = edge_stop(m, ct, e, ring, tris);
      s.stop = s.stop || whole;  // C5: every edge of a whole vertex has its midpoint
      if (!s.stop) continue;
      ct.edge_bits[ei] |= std::uint8_t(CutTopology::kStop | (s.caps_a ? kCapsA : 0) | (s.caps_b ? kCapsB : 0));
    }
  });
  std::vector<std::uint8_t> ends(m.num_vertices(), 0);
  for (std::size_t ei = 0; ei < m.num_edges(); ++ei) {
    std::uint8_t& bits = ct.edge_bits[ei];
    if (!(bits & CutTopology::kStop)) continue;
    const auto [a, b] = m.edge(EdgeId(ei));
    if ((bits & kCapsA) && ends[a.idx] < 3) ++ends[a.idx];
    if ((bits & kCapsB) && ends[b.idx] < 3) ++ends[b.idx];
    bits &= std::uint8_t(~(kCapsA | kCapsB));
  }
  ct.vertex_point.assign(m.num_vertices(), 0);
  for (std::size_t v = 0; v < m.num_vertices(); ++v)
    ct.vertex_point[v] = char(m.vertex_class(VertexId(v)).dim == 0 || ends[v] >= 3);
  return ct;
}

}  // namespace polydual
