// Paper Algorithm 1, step by step (design §4):
//   STEP 1-4  dual points: tet and model-face triangle central points, model-edge
//             midpoints, model vertices;
//   hints     for STEP 9: exact coincidences and short tet-centre edges, found
//             from the primal while the centres' error bounds are in memory;
//   STEP 5-6  one dual face per fan of every primal edge;
//   STEP 7    capping faces, one per run of model-face triangles around a vertex;
//   STEP 9    cleanup (lib/dual/cleanup.cpp: exact merge, short-edge collapse);
//   STEP 8    cells: one per side of every primal vertex.
#include "dual/build_dual.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <functional>
#include <limits>
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include "core/bits.h"
#include "core/error.h"
#include "core/param_range.h"
#include "core/radix_sort.h"
#include "dual/central_points.h"
#include "dual/cleanup.h"
#include "dual/cut_topology.h"
#include "dual/edge_face_blocks.h"
#include "dual/sides.h"
#include "predicates/predicates.h"

namespace polydual {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Dual point ids of a sparse subset of primal entities (model-face triangles,
// model-edge edges), numbered consecutively in entity order from `first`: one
// bit per entity and a running count per 64 (a rank query), instead of a
// 4-byte id per entity at the memory peak.
class SparsePoints {
 public:
  void init(std::size_t n) { bits_.assign((n + 63) / 64, 0); }
  void set(std::size_t i) { bits_[i >> 6] |= std::uint64_t(1) << (i & 63); }
  void finish(std::uint32_t first) {
    first_ = first;
    prefix_.resize(bits_.size());
    std::uint32_t sum = 0;
    for (std::size_t b = 0; b < bits_.size(); ++b) { prefix_[b] = sum; sum += std::uint32_t(popcount64(bits_[b])); }
  }
  bool has(std::size_t i) const { return (bits_[i >> 6] >> (i & 63)) & 1u; }
  // Rank of entity i among the set ones (i must be set).
  std::uint32_t rank(std::size_t i) const {
    const std::uint64_t below = bits_[i >> 6] & ((std::uint64_t(1) << (i & 63)) - 1);
    return prefix_[i >> 6] + std::uint32_t(popcount64(below));
  }
  PointId operator[](std::size_t i) const { return has(i) ? PointId(first_ + rank(i)) : PointId::invalid(); }
  // Calls f(i, rank of i) for the set entities in increasing order (64 at a
  // time: the unset ones cost nothing).
  template <class F>
  void for_each(F&& f) const { for_each_in_words(0, bits_.size(), f); }
  // The same for the entities of words [w0, w1) (64 entities a word; after
  // finish()): disjoint word ranges can run in parallel, as can set() on them.
  template <class F>
  void for_each_in_words(std::size_t w0, std::size_t w1, F&& f) const {
    std::uint32_t r = w0 < prefix_.size() ? prefix_[w0] : 0;
    for (std::size_t b = w0; b < w1; ++b)
      for (std::uint64_t w = bits_[b]; w != 0; w &= w - 1) f(64 * b + std::size_t(std::countr_zero(w)), r++);
  }
  std::size_t num_words() const { return bits_.size(); }
  std::uint32_t count() const { return prefix_.empty() ? 0 : prefix_.back() + std::uint32_t(popcount64(bits_.back())); }

 private:
  std::vector<std::uint64_t> bits_;
  std::vector<std::uint32_t> prefix_;
  std::uint32_t first_ = 0;
};

struct DualPoints {
  SparsePoints tri_point;           // model-face triangles
  SparsePoints edge_point;          // model-edge edges
  std::vector<PointId> vert_point;  // per vertex (model vertices only)
  // CentralPoint::error of a well-centred tet's centre; -inf marks a clamped
  // centre (no tolerance admits it in the coincidence test).
  std::vector<double> tet_centre_error;
  std::vector<char> tri_well_centred;  // by rank among the model-face triangles
  std::vector<char> pinned;            // per point, empty without whole cuts (cut_topology.h)
};

// Whether edge e / vertex v gets a dual point: on a model edge / at a model
// vertex (the paper), where cuts say so (cut_topology.h), and in keep mode on
// every model entity (an edge or vertex classified in dimension <= 2).
// Per vertex k of triangle f: whether the edge opposite it is on a model edge.
std::array<bool, 3> model_edges_opposite(const ClassifiedTetMesh& m, TriId f) {
  const auto& v = m.triangle(f);
  std::array<bool, 3> out{};
  for (int k = 0; k < 3; ++k) out[k] = m.edge_class(m.triangle_edge(f, v[(k + 1) % 3], v[(k + 2) % 3])).dim <= 1;
  return out;
}

bool edge_has_point(const ClassifiedTetMesh& m, const CutTopology& ct, bool keep, EdgeId e) {
  if (keep && m.edge_class(e).dim <= 2) return true;
  return ct.active ? ct.stop(e) : m.edge_class(e).dim == 1;
}
bool vertex_has_point(const ClassifiedTetMesh& m, const CutTopology& ct, bool keep, VertexId v) {
  if (keep && m.vertex_class(v).dim <= 2) return true;
  return ct.active ? ct.vertex_point[v.idx] != 0 : m.vertex_class(v).dim == 0;
}

// STEP 1-4. Tet centers get PointId == TetId. With cuts (cut_topology.h) the
// cut triangles get centres among the model-face triangles' (classified in
// their region), the stop edges midpoints and the vertices it names points.
// Every point records the primal entity it comes from (point_origin).
// Keep mode (BoundaryMode::Keep): model-face triangles get
// triangle_inner_point(), never merged (tri_well_centred off), and every edge
// and vertex on a model entity gets a point (edge_has_point, vertex_has_point).
DualPoints make_points(const ClassifiedTetMesh& m, const CutTopology& ct, bool keep, PolyMesh& pm, DualStats& st) {
  DualPoints d;
  const std::size_t nt = m.num_tets();
  pm.points.resize(nt);
  pm.point_class.resize(nt);
  pm.point_origin.resize(nt);
  auto add = [&](const Point3& p, ModelRef cls, std::int8_t dim, std::size_t id) {
    pm.points.push_back(p);
    pm.point_class.push_back(cls);
    pm.point_origin.push_back(PointOrigin{dim, std::uint32_t(id)});
  };
  d.tet_centre_error.resize(nt);
  const bool pin = ct.active && !ct.cuts->whole.empty();
  // Independent per tet: parallel, and the same result for any thread count.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nt, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t t = r.begin(); t < r.end(); ++t) {
      const auto& v = m.tet(TetId(t));
      CentralPoint c = tet_central_point(m.point(v[0]), m.point(v[1]), m.point(v[2]), m.point(v[3]));
      if (pin && pinned(m, ct.cuts, PointOrigin{3, std::uint32_t(t)})) {  // C5: the centroid, never merged
        c.p = barycentre(m, PointOrigin{3, std::uint32_t(t)});
        c.well_centred = false;
      }
      pm.points[t] = c.p;
      pm.point_class[t] = ModelRef{3, m.region(TetId(t))};
      pm.point_origin[t] = PointOrigin{3, std::uint32_t(t)};
      d.tet_centre_error[t] = c.well_centred ? c.error : -std::numeric_limits<double>::infinity();
    }
  });
  st.well_centred_tets = std::size_t(std::count_if(d.tet_centre_error.begin(), d.tet_centre_error.end(),
                                                   [](double e) { return e >= 0; }));
  st.clamped_tets = nt - st.well_centred_tets;
  // The model-face and cut triangles' centres: which ones first (disjoint
  // 64-triangle words in parallel), then their centres in parallel, each
  // written at its rank (the same points, in triangle order, for any thread
  // count).
  d.tri_point.init(m.num_triangles());
  const std::size_t num_words = d.tri_point.num_words();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_words, 256), [&](const auto& r) {
    const std::size_t f1 = std::min(m.num_triangles(), 64 * r.end());
    for (std::size_t f = 64 * r.begin(); f < f1; ++f)
      if (m.on_model_face(TriId(f)) || ct.is_cut(TriId(f))) d.tri_point.set(f);
  });
  const std::uint32_t first_tri_point = std::uint32_t(pm.num_points());
  d.tri_point.finish(first_tri_point);
  const std::size_t num_tri_points = d.tri_point.count();
  pm.points.resize(first_tri_point + num_tri_points);
  pm.point_class.resize(first_tri_point + num_tri_points);
  pm.point_origin.resize(first_tri_point + num_tri_points);
  d.tri_well_centred.resize(num_tri_points);
  const std::size_t well_centred = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, num_words, 256), std::size_t(0),
      [&](const tbb::blocked_range<std::size_t>& r, std::size_t n) {
        d.tri_point.for_each_in_words(r.begin(), r.end(), [&](std::size_t f, std::uint32_t rank) {
          const bool model = m.on_model_face(TriId(f));
          const auto& v = m.triangle(TriId(f));
          CentralPoint c = keep && model ? triangle_inner_point(m.point(v[0]), m.point(v[1]), m.point(v[2]))
                           : model       ? cap_triangle_point(m.point(v[0]), m.point(v[1]), m.point(v[2]),
                                                              model_edges_opposite(m, TriId(f)).data())
                                         : triangle_central_point(m.point(v[0]), m.point(v[1]), m.point(v[2]));
          if (pin && pinned(m, ct.cuts, PointOrigin{2, std::uint32_t(f)})) {
            c.p = barycentre(m, PointOrigin{2, std::uint32_t(f)});
            c.well_centred = false;
          }
          const std::size_t p = first_tri_point + rank;
          pm.points[p] = c.p;
          pm.point_class[p] = model ? m.triangle_class(TriId(f)) : ModelRef{3, m.region(m.triangle_tet(TriId(f), 0))};
          pm.point_origin[p] = PointOrigin{2, std::uint32_t(f)};
          // A cut triangle's centre is never merged (cleanup_dual: no merge across cuts).
          d.tri_well_centred[rank] = char(model && c.well_centred && !keep);
          n += c.well_centred;
        });
        return n;
      },
      std::plus<std::size_t>());
  st.well_centred_triangles += well_centred;
  st.clamped_triangles += num_tri_points - well_centred;
  d.edge_point.init(m.num_edges());
  const std::uint32_t first_edge_point = std::uint32_t(pm.num_points());
  for (std::size_t e = 0; e < m.num_edges(); ++e) {
    if (!edge_has_point(m, ct, keep, EdgeId(e))) continue;
    const auto& v = m.edge(EdgeId(e));
    add(0.5 * (m.point(v[0]) + m.point(v[1])), m.edge_class(EdgeId(e)), 1, e);
    d.edge_point.set(e);
  }
  d.edge_point.finish(first_edge_point);
  d.vert_point.assign(m.num_vertices(), PointId::invalid());
  for (std::size_t v = 0; v < m.num_vertices(); ++v)
    if (vertex_has_point(m, ct, keep, VertexId(v))) {
      d.vert_point[v] = PointId(pm.num_points());
      add(m.point(VertexId(v)), m.vertex_class(VertexId(v)), 0, v);
    }
  if (pin) {
    d.pinned.resize(pm.num_points());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pm.num_points(), 8192), [&](const auto& r) {
      for (std::size_t p = r.begin(); p < r.end(); ++p) d.pinned[p] = char(pinned(m, ct.cuts, pm.point_origin[p]));
    });
  }
  return d;
}

// STEP 5-6: faces of primal edges, one per fan.
// The faces with a model point (triangle centre, midpoint) are listed in
// model_faces: the cleanup walks only their loops for short edges.
// With cuts, the ring of e = (a, b) is cut at the triangles of M ∪ cut(a) ∪
// cut(b) (ring_position), and a triangle cut only by its third vertex keeps
// the ring whole but puts its centre between its two tets (rule I of
// proofs/dual_cuts.md: the cells of a and b stay closed). Instantiated
// without cuts apart (kCuts false): the same code as Algorithm 1 alone.
// Flattened: the chain and emit lambdas, the ring and side lookups inline
// into the edge loop (as calls they cost ~5% of the dual's instructions,
// callgrind).
// The faces of edges [e0, e1) are appended to pm (its face arrays only).
template <bool kCuts>
[[gnu::flatten]] void make_edge_faces(const ClassifiedTetMesh& m, const CutTopology& ct, const VertexSides& sides,
                     const DualPoints& d, PolyMesh& pm, std::vector<std::uint32_t>& model_faces,
                     std::span<const char> active, std::size_t e0, std::size_t e1, std::size_t& walked) {
  std::vector<TetId> ring;
  std::vector<TriId> tris;
  std::vector<std::size_t> cuts;
  std::vector<char> inserted;  // per ring triangle, with cuts only
  std::vector<PointId> loop;
  for (std::size_t e = e0; e < e1; ++e) {
    const EdgeId eid(e);
    if (!active.empty() && !active[m.edge(eid)[0].idx] && !active[m.edge(eid)[1].idx]) continue;  // DualScope
    if (m.edge_class(eid).dim == 3 && (!kCuts || !ct.ring_cut(eid))) {
      // Classified in a region: no model-face triangle around it (classify()),
      // so the ring is closed; with no cut triangle in it either, it is uncut:
      // one face of the tet centres (what the general path below gives).
      const auto [a, b] = m.edge(eid);
      const std::size_t before = pm.face_points.size();
      m.for_each_closed_ring_tet(eid, [&](TetId t) { pm.face_points.push_back(PointId(t.idx)); });
      walked += pm.face_points.size() - before;
      const TetId t0 = m.edge_tet(eid);
      pm.close_face(sides.cell(t0, a), sides.cell(t0, b), FaceKind::Interior, 0);
      continue;
    }
    const VertexId a = m.edge(eid)[0], b = m.edge(eid)[1];
    // Every chain of the edge's ring has its fans (several chains where the
    // mesh touches itself along the edge: proofs/edge_chains.md).
    m.for_each_edge_chain(eid, ring, tris, [&](bool closed) {
      const std::size_t n = ring.size();
      walked += n;
      cuts.clear();
      if constexpr (!kCuts) {
        for (std::size_t k = 0; k < n; ++k)
          if (m.on_model_face(tris[k])) cuts.push_back(k);
      } else {
        inserted.assign(n + 1, 0);
        for (std::size_t k = 0; k < n; ++k) {
          if (ring_position(m, ct, tris[k], a, b)) cuts.push_back(k);
          else inserted[k] = char(ct.is_cut(tris[k]));
        }
        if (closed) inserted[n] = inserted[0];
      }
      if (!closed) cuts.push_back(n);  // tris[n] is the closing boundary triangle
      // The fan of tets ring[s .. t) (indices mod n on a closed ring), between the
      // model-face (or cut) triangles tris[s] and tris[t] when `bounded`. tris has
      // n + 1 entries and tris[n] == tris[0] on a closed ring, so t <= 2n - 1 maps
      // to tris[t - n] past the end.
      auto emit = [&](std::size_t s, std::size_t t, bool bounded) {
        loop.clear();
        const TriId start = tris[s], end = tris[t > n ? t - n : t];
        if (bounded) loop.push_back(d.tri_point[start.idx]);
        if constexpr (!kCuts) {
          for (std::size_t k = s; k < std::min(t, n); ++k) loop.push_back(PointId(ring[k].idx));
          for (std::size_t k = n; k < t; ++k) loop.push_back(PointId(ring[k - n].idx));  // wrapped
        } else {
          for (std::size_t k = s; k < t; ++k) {
            const std::size_t kk = k >= n ? k - n : k;
            if (k > s && inserted[kk]) loop.push_back(d.tri_point[tris[kk].idx]);
            loop.push_back(PointId(ring[kk].idx));
          }
          if (!bounded && inserted[0]) loop.push_back(d.tri_point[tris[0].idx]);  // between ring[n-1] and ring[0]
        }
        // One cut on a closed ring (start == end, a fracture tip edge): the fan
        // goes all the way round and closes on the start triangle's centre.
        if (bounded && end != start) {
          loop.push_back(d.tri_point[end.idx]);
          if (d.edge_point[e].valid()) loop.push_back(d.edge_point[e]);
        }
        const TetId t0 = ring[s % n];
        if (bounded) model_faces.push_back(std::uint32_t(pm.num_faces()));
        pm.add_face(loop, sides.cell(t0, a), sides.cell(t0, b),
                    FaceKind::Interior, 0);
      };
      if (cuts.empty()) {
        emit(0, n, false);  // interior edge: closed ring, no model face
      } else if (!closed) {
        for (std::size_t j = 0; j + 1 < cuts.size(); ++j) emit(cuts[j], cuts[j + 1], true);
      } else {
        for (std::size_t j = 0; j < cuts.size(); ++j)
          emit(cuts[j], j + 1 < cuts.size() ? cuts[j + 1] : cuts[0] + n, true);
      }
    });
  }
}

// Every edge's faces, in edge order (dual/edge_face_blocks.h). Returns the
// number of tets the ring walks visited (6 per tet when every chain of every
// edge was walked).
template <bool kCuts>
std::size_t make_all_edge_faces(const ClassifiedTetMesh& m, const CutTopology& ct, const VertexSides& sides,
                                const DualPoints& d, PolyMesh& pm, std::vector<std::uint32_t>& model_faces,
                                std::span<const char> active) {
  return make_faces_in_blocks(m.num_edges(), 2048, pm, model_faces,
                              [&](std::size_t e0, std::size_t e1, EdgeFaceBlock& b) {
                                make_edge_faces<kCuts>(m, ct, sides, d, b.faces, b.model_faces, active, e0, e1,
                                                       b.walked);
                              });
}

// Every tet lies around its 6 edges, so the ring walks of all edges visit
// 6 tets per tet exactly when every chain of every edge was walked. Fewer
// happens only when the tets around some edge hold a closed chain and another
// one, which winds round the edge more than once: the tets overlap there
// (proofs/edge_chains.md E1). Such a mesh is refused (InputError naming the
// edge, input numbering) rather than given a dual with open cells. The edge
// is found only on this error path: the tets around each edge counted
// against its walks.
void refuse_overlapping_rings(const ClassifiedTetMesh& m, std::size_t walked) {
  if (walked == 6 * m.num_tets()) [[likely]]
    return;
  std::vector<std::uint32_t> around(m.num_edges(), 0);
  for (std::size_t t = 0; t < m.num_tets(); ++t)
    for (int k = 0; k < 6; ++k) ++around[m.tet_edge(TetId(t), k).idx];
  std::vector<TetId> ring;
  std::vector<TriId> tris;
  for (std::size_t e = 0; e < m.num_edges(); ++e) {
    std::size_t n = 0;
    m.for_each_edge_chain(EdgeId(e), ring, tris, [&](bool) { n += ring.size(); });
    if (n == around[e]) continue;
    // Every chain of the edge, the closed ones counted apart (for the message).
    bool closed;
    m.edge_ring(EdgeId(e), ring, tris, closed);
    std::size_t in_rings = closed ? ring.size() : 0;
    for (TetId start : m.other_chain_starts(EdgeId(e), ring)) {
      std::vector<TetId> chain;
      m.edge_ring_from(EdgeId(e), start, chain, tris, closed);
      in_rings += closed ? chain.size() : 0;
    }
    const auto [a, b] = m.edge(EdgeId(e));
    throw InputError(m.source(),
                     "edge (" + std::to_string(m.input_vertex(a) + 1) + ", " + std::to_string(m.input_vertex(b) + 1) + ")",
                     "the tets around this edge overlap: " + std::to_string(in_rings) +
                         " of them close a ring round it and " + std::to_string(around[e] - in_rings) +
                         (around[e] - in_rings == 1 ? " more lies" : " more lie") + " around it too");
  }
}

// Vertex v -> the triangles of M ∪ cut(v) through v (CSR, triangles
// increasing per vertex).
struct VertexTriangles {
  std::vector<std::uint32_t> off;
  std::vector<TriId> tri;
  std::span<const TriId> of(std::size_t v) const { return {tri.data() + off[v], tri.data() + off[v + 1]}; }
};

VertexTriangles vertex_cap_triangles(const ClassifiedTetMesh& m, const CutTopology& ct) {
  const std::size_t nv = m.num_vertices(), nf = m.num_triangles();
  VertexTriangles vt;
  vt.off.assign(nv + 1, 0);
  for (std::size_t f = 0; f < nf; ++f)
    if (m.on_model_face(TriId(f)))
      for (VertexId v : m.triangle(TriId(f))) ++vt.off[v.idx + 1];
  if (ct.active)
    for (std::size_t v = 0; v < nv; ++v) vt.off[v + 1] += std::uint32_t(ct.cuts->of(VertexId(v)).size());
  for (std::size_t v = 0; v < nv; ++v) vt.off[v + 1] += vt.off[v];
  vt.tri.resize(vt.off[nv]);
  std::vector<std::uint32_t> fill(vt.off.begin(), vt.off.end() - 1);
  for (std::size_t f = 0; f < nf; ++f)
    if (m.on_model_face(TriId(f)))
      for (VertexId v : m.triangle(TriId(f))) vt.tri[fill[v.idx]++] = TriId(f);
  if (ct.active)
    for (std::size_t v = 0; v < nv; ++v) {
      for (TriId f : ct.cuts->of(VertexId(v))) vt.tri[fill[v]++] = f;
      std::sort(vt.tri.begin() + vt.off[v], vt.tri.begin() + vt.off[v + 1],
                [](TriId x, TriId y) { return x.idx < y.idx; });
    }
  return vt;
}

// The runs of cap triangles (M ∪ cut(v)) around one vertex v (STEP 7). Each
// triangle k of L is seen as (v, A[k], B[k]) in its stored orientation, with
// whether the edges (v, A[k]), (v, B[k]) are stop edges (model edges, and with
// cuts CutTopology::stop: a run stops there).
// The buffers are reused from vertex to vertex.
struct CapRuns {
  struct Oriented { std::uint32_t k; VertexId p, q; };  // triangle L[k] seen as (v, p, q)
  std::vector<VertexId> A, B;
  std::vector<char> stopA, stopB, visited;
  std::vector<Oriented> seq;  // the current run, in walk order
  std::uint32_t n = 0;

  void load(const ClassifiedTetMesh& m, const CutTopology& ct, VertexId v, std::span<const TriId> L) {
    n = std::uint32_t(L.size());
    A.resize(n);
    B.resize(n);
    stopA.resize(n);
    stopB.resize(n);
    visited.assign(n, 0);
    for (std::uint32_t k = 0; k < n; ++k) {
      const auto t = m.triangle(L[k]);  // outward from triangle_tet(L[k], 0)
      const int i = t[0] == v ? 0 : (t[1] == v ? 1 : 2);
      A[k] = t[(i + 1) % 3];
      B[k] = t[(i + 2) % 3];
      const EdgeId ea = m.triangle_edge(L[k], v, A[k]), eb = m.triangle_edge(L[k], v, B[k]);
      stopA[k] = ct.active ? ct.stop(ea) : m.edge_class(ea).dim == 1;
      stopB[k] = ct.active ? ct.stop(eb) : m.edge_class(eb).dim == 1;
    }
  }
  // The run triangle other than k sharing edge (v, w), or -1 at a stop edge
  // (any other edge has exactly two run triangles, of one model face or both
  // cut: proofs/dual_cuts.md).
  // Found without branches: L is short, and which j matches is a coin toss.
  [[gnu::always_inline]] std::int64_t across(std::uint32_t k, VertexId w) const {
    if (w == A[k] ? stopA[k] : stopB[k]) return -1;
    std::int64_t hit = -1;
    for (std::uint32_t j = n; j-- > 0;) {
      const std::int64_t h = std::int64_t((j != k) & ((A[j] == w) | (B[j] == w)));
      hit ^= (hit ^ std::int64_t(j)) & -h;  // a mask: ?: here compiles to a branch
    }
    return hit;
  }
  // The vertex of L[j] other than v and w.
  VertexId other_than(std::uint32_t j, VertexId w) const { return A[j] == w ? B[j] : A[j]; }

  // The run through triangle i0 into seq (from its start if the run is open);
  // returns whether it is closed (goes all the way round v).
  bool walk(std::uint32_t i0) {
    const Oriented first{i0, A[i0], B[i0]};
    // Walk backwards to the start of an open run.
    Oriented start = first;
    bool closed = false;
    for (;;) {
      const std::int64_t g = across(start.k, start.p);
      if (g < 0) break;
      if (std::uint32_t(g) == first.k) { closed = true; break; }
      start = Oriented{std::uint32_t(g), other_than(std::uint32_t(g), start.p), start.p};
    }
    // Walk forwards collecting the run.
    seq.clear();
    Oriented cur = start;
    for (;;) {
      seq.push_back(cur);
      visited[cur.k] = 1;
      const std::int64_t g = across(cur.k, cur.q);
      if (g < 0 || std::uint32_t(g) == start.k) break;
      cur = Oriented{std::uint32_t(g), cur.q, other_than(std::uint32_t(g), cur.q)};
    }
    return closed;
  }
};

// The loop of the cap of the run in runs.seq around v. Returns true when the
// run leaves and re-enters through the same model edge (a model edge ending
// at v inside the face, such as the seam of a Gmsh sphere at its pole): the
// loop [edge midpoint, triangle points...] then winds once round v, which
// make_caps puts on the cap by splitting it (add_cap).
bool cap_loop(const ClassifiedTetMesh& m, const DualPoints& d, VertexId v, std::span<const TriId> L,
              const CapRuns& runs, bool closed, std::vector<PointId>& loop) {
  const auto& seq = runs.seq;
  loop.clear();
  if (!closed) loop.push_back(d.edge_point[m.triangle_edge(L[seq.front().k], v, seq.front().p).idx]);
  for (const CapRuns::Oriented& o : seq) loop.push_back(d.tri_point[L[o.k].idx]);
  if (closed) return false;
  if (seq.front().p == seq.back().q) return true;
  loop.push_back(d.edge_point[m.triangle_edge(L[seq.back().k], v, seq.back().q).idx]);
  if (d.vert_point[v.idx].valid()) loop.push_back(d.vert_point[v.idx]);
  return false;
}

// Adds the cap `loop` as one face, or, when it winds round the model vertex
// v through one model edge's midpoint e (cap_loop's true: loop = e, t1..tk),
// as the two faces (v, e, t1..tj) and (v, tj..tk, e), j = ceil(k/2): the
// model vertex gets its dual point (going out to v and back through e in one
// loop would repeat e, which no polyhedral format accepts). The edges (v, e)
// and (v, tj) are used once each way by the two faces, the rest as by the
// one loop: the cell stays closed (proofs/dual_invariants.md L1).
void add_cap(PolyMesh& pm, const std::vector<PointId>& loop, bool round_v, PointId v_point, CellId owner,
             CellId neigh, FaceKind kind, std::int32_t tag) {
  const std::size_t k = loop.size() - 1;  // the triangle points t1..tk follow e
  if (!round_v || !v_point.valid() || k < 2) {
    pm.add_face(loop, owner, neigh, kind, tag);
    return;
  }
  const std::size_t j = (k + 1) / 2;
  std::vector<PointId> a{v_point}, b{v_point};
  a.insert(a.end(), loop.begin(), loop.begin() + static_cast<std::ptrdiff_t>(j + 1));  // e, t1..tj
  b.insert(b.end(), loop.begin() + static_cast<std::ptrdiff_t>(j), loop.end());       // tj..tk
  b.push_back(loop.front());                                                            // e
  pm.add_face(a, owner, neigh, kind, tag);
  pm.add_face(b, owner, neigh, kind, tag);
}

// Keep mode's cap of the model-face run in runs.seq around v (BoundaryMode::
// Keep): the quads (v, mid(v p), centre(t), mid(v q)) of its triangles
// t = (v, p, q), consecutive ones merged while their triangles are coplanar
// (EXACT: orient3d of the two triangles' four vertices is zero), each group
// one face [v, mid(v p_i), c_i, mid(v q_i), c_i+1, ..., c_j, mid(v q_j)] in the
// run's orientation (the caps' own). A closed run whose triangles are all
// coplanar is the one face [mid(v p_0), c_0, mid(v p_1), c_1, ...] round v
// (v lies inside it: no point needed there), unless v is a model vertex where
// faces touch without a model edge (touch_vertex): two groups. A run that leaves and re-enters
// through one model edge (a pole on a seam: p_0 == q_last) is never one group,
// whose loop would repeat that edge's midpoint: it is cut in two at its middle.
void keep_cap_faces(const ClassifiedTetMesh& m, const DualPoints& d, VertexId v, std::span<const TriId> L,
                    const CapRuns& runs, bool closed, bool touch, std::vector<std::vector<PointId>>& faces) {
  const auto& seq = runs.seq;
  const std::size_t n = seq.size();
  faces.clear();
  auto mid = [&](std::size_t i, VertexId w) { return d.edge_point[m.triangle_edge(L[seq[i].k], v, w).idx]; };
  auto centre = [&](std::size_t i) { return d.tri_point[L[seq[i].k].idx]; };
  // starts[i]: a group starts at seq[i] (its triangle is not coplanar with the previous one).
  std::vector<char> starts(n, 0);
  std::size_t num_starts = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (i == 0 && !closed) { starts[0] = 1; ++num_starts; continue; }
    const auto& a = seq[(i + n - 1) % n];
    starts[i] = char(orient3d(m.point(v), m.point(a.p), m.point(a.q), m.point(seq[i].q)) != Sign::Zero);
    num_starts += starts[i];
  }
  if (closed && num_starts == 0 && touch && n >= 2) starts[0] = starts[n / 2] = 1;  // through a touch vertex
  else if (closed && num_starts == 0) {
    faces.emplace_back();
    for (std::size_t i = 0; i < n; ++i) {
      faces.back().push_back(mid(i, seq[i].p));
      faces.back().push_back(centre(i));
    }
    return;
  }
  if (!closed && num_starts == 1 && seq.front().p == seq.back().q) starts[n / 2] = 1;  // n >= 2 round a pole
  std::size_t first = 0;
  while (!starts[first]) ++first;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = (first + k) % n;
    if (starts[i]) faces.push_back({d.vert_point[v.idx], mid(i, seq[i].p)});
    faces.back().push_back(centre(i));
    faces.back().push_back(mid(i, seq[i].q));
  }
}

// A model vertex with a dual point where no run stops: model faces touch
// there without a model edge (a fracture touching an interface at one vertex,
// proofs/classification.md L11(d)). Every run round it is closed, so no cap
// would pass through its point; make_caps cuts each closed run in two there
// (add_cap with the loop's first triangle point as the pivot, keep_cap_faces
// with two groups), as for a pole (proofs/dual_invariants.md L4).
bool touch_vertex(const ClassifiedTetMesh& m, const DualPoints& d, VertexId v, const CapRuns& runs) {
  if (m.vertex_class(v).dim != 0 || !d.vert_point[v.idx].valid()) return false;
  for (std::uint32_t k = 0; k < runs.n; ++k)
    if (runs.stopA[k] || runs.stopB[k]) return false;
  return true;
}

// STEP 7: capping faces. Around each vertex v, walk the triangles of M ∪
// cut(v) containing v through edges (v,w) that are not stop edges (such an
// edge has exactly two of them, of one model face or both cut): each walk is
// a run. A cap on cut triangles is an interior face between two sides of v.
// In keep mode (BoundaryMode::Keep) a run on a model face is tiled by
// keep_cap_faces instead; cut runs are capped as in the paper either way.
void make_caps(const ClassifiedTetMesh& m, const CutTopology& ct, const VertexSides& sides, const DualPoints& d,
               bool keep, PolyMesh& pm, DualStats& st, std::span<const char> active) {
  const VertexTriangles vt = vertex_cap_triangles(m, ct);
  CapRuns runs;
  std::vector<PointId> loop;
  std::vector<std::vector<PointId>> tiles;
  for (std::size_t vi = 0; vi < m.num_vertices(); ++vi) {
    const VertexId v(vi);
    const std::span<const TriId> L = vt.of(vi);
    if (L.empty() || (!active.empty() && !active[vi])) continue;
    runs.load(m, ct, v, L);
    const bool touch = touch_vertex(m, d, v, runs);
    for (std::uint32_t i0 = 0; i0 < runs.n; ++i0) {
      if (runs.visited[i0]) continue;
      const bool closed = runs.walk(i0);
      const bool tiled = keep && m.on_model_face(L[i0]);
      const bool round_v = !tiled && (cap_loop(m, d, v, L, runs, closed, loop) || (closed && touch));
      if (tiled) keep_cap_faces(m, d, v, L, runs, closed, touch, tiles);
      // The loop follows the orientation of L[i0] (the walk's `first`, whose
      // orientation every triangle of the walk inherits), so the owner is the
      // side of the tet that L[i0]'s stored orientation points out of.
      const TriId f0 = L[i0];
      const TetId t0 = m.triangle_tet(f0, 0), t1 = m.triangle_tet(f0, 1);
      const CellId owner = sides.cell(t0, v);
      const CellId neigh = t1.valid() ? sides.cell(t1, v) : CellId::invalid();
      if (owner == neigh) ++st.slit_faces;
      const PointId vp = d.vert_point[v.idx];
      if (tiled) {
        const std::int32_t tag = m.triangle_class(f0).tag;
        for (const auto& tile : tiles) pm.add_face(tile, owner, neigh, m.model().face_kind(tag), tag);
      } else if (m.on_model_face(f0)) {
        const std::int32_t tag = m.triangle_class(f0).tag;
        add_cap(pm, loop, round_v, vp, owner, neigh, m.model().face_kind(tag), tag);
      } else {
        add_cap(pm, loop, round_v, vp, owner, neigh, FaceKind::Interior, 0);
      }
    }
  }
}

// Pairs of dual points that coincide exactly: face-adjacent well-centred tets
// of one region that are cospherical (EXACT insphere == 0), not across a model
// face; and adjacent well-centred model-face triangles of one model face that
// are cocircular (EXACT: coplanar and cospherical with an off-plane point).
// Also the candidates for the short-edge collapse among the dual edges that
// join two tet centres: such an edge crosses an interior triangle not on a
// model face (consecutive tets of a fan share one), so these are found here,
// once per triangle, not once per face loop the edge is in (three).
struct PointPairs {
  std::vector<std::pair<PointId, PointId>> exact, short_;
};

// The coincidence test adds the two centres' error bounds; the sum is rounded
// too, and a bound that is a hair too small would skip a needed exact test
// (an unmerged pair), so it is widened by 0.1 %. Too wide costs only an
// insphere test (which decides).
constexpr double kBoundSlack = 1.001;

// Tet centres across a cut triangle are never paired: the dual edge between
// them may not exist (the triangle's centre sits between them, or the cut
// separates them).
PointPairs point_pairs(const ClassifiedTetMesh& m, const CutTopology& ct, const DualPoints& d, const PolyMesh& pm,
                       double collapse_length) {
  PointPairs out;
  auto& pairs = out.exact;
  const double lim2 = collapse_length * collapse_length;
  // Each interior triangle once, from its smaller tet t0; the neighbour's
  // vertex across it is the one opposite the shared face. Whether a face
  // is seen from its smaller tet is a coin toss, so the faces of a block of
  // tets are gathered without branches first (written always, counted by the
  // flag), then tested. The tests reject almost every face before the
  // (costlier) lookup of the triangle's model face.
  const std::size_t nt = m.num_tets();
  constexpr std::size_t kBlock = 4096;
  std::vector<std::uint32_t> cand(4 * kBlock);
  for (std::size_t begin = 0; begin < nt; begin += kBlock) {
    const std::size_t end = std::min(nt, begin + kBlock);
    std::size_t n = 0;
    for (std::size_t t = begin; t < end; ++t)
      for (int i = 0; i < 4; ++i) {
        const TetId t1 = m.tet_neighbor(TetId(t), i);
        cand[n] = std::uint32_t(4 * t + std::size_t(i));
        n += std::uint32_t(t1.valid()) & std::uint32_t(t1.idx > t);
      }
    for (std::size_t k = 0; k < n; ++k) {
      const TetId t0(cand[k] >> 2);
      const int i = int(cand[k] & 3);
      const TetId t1 = m.tet_neighbor(t0, i);
      const Point3 &c0 = pm.points[t0.idx], &c1 = pm.points[t1.idx];
      const Vec3 dc = c1 - c0;
      // Inexact: a length threshold is a tolerance, not a sign.
      if (dot(dc, dc) < lim2) [[unlikely]] {
        const TriId f = m.tet_triangle(t0, i);
        const bool pin = !d.pinned.empty() && (d.pinned[t0.idx] || d.pinned[t1.idx]);
        if (!m.on_model_face(f) && !ct.is_cut(f) && !pin) out.short_.emplace_back(PointId(t0.idx), PointId(t1.idx));
      }
      // Cospherical (sharing a face) iff the exact circumcentres coincide. If
      // the rounded centres differ by more than their error bounds (L9c), they
      // do not: no insphere test needed. Otherwise the exact test decides. A
      // clamped centre's bound is -inf: no tolerance admits it.
      const double tol = kBoundSlack * (d.tet_centre_error[t0.idx] + d.tet_centre_error[t1.idx]);
      if (std::fabs(dc.x) > tol || std::fabs(dc.y) > tol || std::fabs(dc.z) > tol) continue;
      if (m.on_model_face(m.tet_triangle(t0, i)) || ct.is_cut(m.tet_triangle(t0, i))) continue;
      const auto& a = m.tet(t0);
      const VertexId far = m.tet(t1)[m.tet_neighbor_face(t0, i)];
      if (insphere(m.point(a[0]), m.point(a[1]), m.point(a[2]), m.point(a[3]), m.point(far)) == Sign::Zero)
        pairs.emplace_back(PointId(t0.idx), PointId(t1.idx));
    }
  }
  // Pairs of well-centred model-face triangles sharing an edge that is not a
  // model edge (such an edge has exactly two, of one model face): their
  // (edge, triangle, opposite vertex) records sorted by edge pair up.
  struct Rec { std::uint32_t e, f; VertexId opp; };
  std::vector<Rec> recs;
  d.tri_point.for_each([&](std::size_t fi, std::uint32_t rank) {
    if (!d.tri_well_centred[rank]) return;
    const TriId f(fi);
    const auto tv = m.triangle(f);
    for (int k = 0; k < 3; ++k) {
      const EdgeId e = m.triangle_edge(f, tv[k], tv[(k + 1) % 3]);
      if (m.edge_class(e).dim == 2) recs.push_back({e.idx, std::uint32_t(fi), tv[(k + 2) % 3]});
    }
  });
  // Stable by edge: records were made in triangle order.
  radix_sort_by_key(recs, [](const Rec& x) { return x.e; }, std::bit_width(m.num_edges()));
  for (std::size_t k = 0; k + 1 < recs.size(); ++k) {
    if (recs[k].e != recs[k + 1].e) continue;
    const auto t = m.triangle(TriId(recs[k].f));
    const Point3 &A = m.point(t[0]), &B = m.point(t[1]), &C = m.point(t[2]);
    const Point3& P = m.point(recs[k + 1].opp);
    if (orient3d(A, B, C, P) != Sign::Zero) continue;
    const Point3 E = A + cross(B - A, C - A);  // off the plane (checked exactly below)
    const Sign o = orient3d(A, B, C, E);
    if (o == Sign::Zero) continue;
    const Sign s = o == Sign::Positive ? insphere(A, B, C, E, P) : insphere(A, C, B, E, P);
    if (s == Sign::Zero) pairs.emplace_back(d.tri_point[recs[k].f], d.tri_point[recs[k + 1].f]);
  }
  return out;
}

double mean_edge_length(const ClassifiedTetMesh& m) {
  double s = 0;
  for (std::size_t e = 0; e < m.num_edges(); ++e)
    s += norm(m.point(m.edge(EdgeId(e))[1]) - m.point(m.edge(EdgeId(e))[0]));
  return m.num_edges() ? s / double(m.num_edges()) : 0.0;
}

// Reserve the dual's arrays up front: growing them by doubling would hold up
// to three copies at the memory peak. Points are counted exactly; faces and
// their point lists are bounded by the edge rings (sum of ring sizes = 6 per
// tet) plus the model-face triangle centres, midpoints and model vertices
// they add (each triangle centre in <= 6 fan faces and 3 caps).
// With cuts the points are still counted exactly (cut triangles, stop edges,
// vertex points); faces may then outgrow the bound (more arcs per ring).
void reserve_dual(const ClassifiedTetMesh& m, const CutTopology& ct, bool keep, PolyMesh& pm) {
  std::size_t nmf = 0, nme = 0, nmv = 0;
  for (std::size_t f = 0; f < m.num_triangles(); ++f) nmf += m.on_model_face(TriId(f)) || ct.is_cut(TriId(f));
  for (std::size_t e = 0; e < m.num_edges(); ++e) nme += edge_has_point(m, ct, keep, EdgeId(e));
  for (std::size_t v = 0; v < m.num_vertices(); ++v) nmv += vertex_has_point(m, ct, keep, VertexId(v));
  const std::size_t np = m.num_tets() + nmf + nme + nmv;
  pm.points.reserve(np);
  pm.point_class.reserve(np);
  pm.point_origin.reserve(np);
  const std::size_t nf = m.num_edges() + (keep ? 3 : 2) * nmf + nme;
  pm.face_offsets.reserve(nf + 1);
  pm.face_owner.reserve(nf);
  pm.face_neighbour.reserve(nf);
  pm.face_kind.reserve(nf);
  pm.face_tag.reserve(nf);
  pm.face_points.reserve(6 * m.num_tets() + 9 * nmf + 4 * nme + nmv);
}

}  // namespace

const char* boundary_mode_name(BoundaryMode m) { return m == BoundaryMode::Keep ? "keep" : "caps"; }

BoundaryMode parse_boundary_mode(std::string_view s) {
  if (s == "keep") return BoundaryMode::Keep;
  if (s == "caps") return BoundaryMode::Caps;
  throw UsageError("DualParams::boundary: '" + std::string(s) + "' is not a boundary mode (keep or caps)");
}

void DualParams::validate() const {
  if (boundary != BoundaryMode::Keep && boundary != BoundaryMode::Caps)
    throw UsageError("DualParams::boundary: " + std::to_string(int(boundary)) + " is not a boundary mode (keep or caps)");
  check_param("DualParams::collapse_tolerance", "relative to the mean primal edge length",
              ParamRange{kMinCollapseTolerance, kMaxCollapseTolerance}, collapse_tolerance);
}

Json DualParams::to_json() const {
  Json j = Json::object();
  j.set("boundary", boundary_mode_name(boundary));
  j.set("cleanup", cleanup);
  j.set("collapse_tolerance", collapse_tolerance);
  return j;
}

Json DualStats::to_json() const {
  Json j = Json::object();
  j.set("well_centred_tets", well_centred_tets);
  j.set("clamped_tets", clamped_tets);
  j.set("well_centred_triangles", well_centred_triangles);
  j.set("clamped_triangles", clamped_triangles);
  j.set("merged_points", merged_points);
  j.set("collapsed_points", collapsed_points);
  j.set("dropped_faces", dropped_faces);
  j.set("slit_faces", slit_faces);
  Json sec = Json::object();
  sec.set("points", seconds_points);
  sec.set("sides", seconds_sides);
  sec.set("faces", seconds_faces);
  sec.set("hints", seconds_hints);
  sec.set("cleanup", seconds_cleanup);
  sec.set("cells", seconds_cells);
  j.set("seconds", sec);
  return j;
}

double dual_collapse_length(const ClassifiedTetMesh& m, const DualParams& params) {
  return params.collapse_tolerance * mean_edge_length(m);
}

DualDraft build_dual_draft(const ClassifiedTetMesh& m, const DualParams& params, DualStats* stats,
                           const VertexCuts* cuts, const DualScope* scope) {
  params.validate();
  if (scope && !scope->active.empty() && scope->active.size() != m.num_vertices())
    throw UsageError("build_dual_draft: DualScope has " + std::to_string(scope->active.size()) +
                     " active flags for " + std::to_string(m.num_vertices()) + " vertices");
  // Point origins hold ids up to PointOrigin::kMaxId (poly_mesh.h).
  if (std::max({m.num_tets(), m.num_triangles(), m.num_edges(), m.num_vertices()}) > PointOrigin::kMaxId)
    throw InputError(m.source(), "", "too large for the dual: more than " + std::to_string(PointOrigin::kMaxId) +
                                         " tets, triangles, edges or vertices");
  DualStats local;
  DualStats& st = stats ? *stats : local;
  DualDraft draft;
  draft.scoped = scope && !scope->active.empty();
  PolyMesh& pm = draft.mesh;
  auto t0 = Clock::now();
  const CutTopology ct = cut_topology(m, cuts);
  const bool keep = params.boundary == BoundaryMode::Keep;
  draft.keep_boundary = keep;
  reserve_dual(m, ct, keep, pm);
  DualPoints d = make_points(m, ct, keep, pm, st);
  st.seconds_points = since(t0);

  // The hints need only the points, the sides neither: both at once. The
  // hints free the centres' error bounds before the faces fill memory.
  VertexSides sides;
  tbb::parallel_invoke(
      [&] {
        const auto t1 = Clock::now();
        if (params.cleanup) {
          draft.collapse_length =
              scope && scope->collapse_length >= 0 ? scope->collapse_length : dual_collapse_length(m, params);
          PointPairs pairs = point_pairs(m, ct, d, pm, draft.collapse_length);
          draft.exact_pairs = std::move(pairs.exact);
          draft.short_pairs = std::move(pairs.short_);
        }
        d.tet_centre_error = std::vector<double>();
        d.tri_well_centred = std::vector<char>();
        draft.pinned = std::move(d.pinned);
        st.seconds_hints = since(t1);
      },
      [&] {
        const auto t1 = Clock::now();
        sides = compute_sides(m, ct.active ? cuts : nullptr);
        st.seconds_sides = since(t1);
      });
  t0 = Clock::now();
  std::vector<std::uint32_t> model_faces;
  const std::span<const char> active = scope ? scope->active : std::span<const char>();
  const std::size_t walked = ct.active ? make_all_edge_faces<true>(m, ct, sides, d, pm, model_faces, active)
                                       : make_all_edge_faces<false>(m, ct, sides, d, pm, model_faces, active);
  if (active.empty()) refuse_overlapping_rings(m, walked);  // a scoped dual walks some edges only
  const std::size_t first_cap = pm.num_faces();
  make_caps(m, ct, sides, d, keep, pm, st, active);  // every cap has model points
  for (std::size_t f = first_cap; f < pm.num_faces(); ++f) model_faces.push_back(std::uint32_t(f));
  if (params.cleanup) draft.scan_faces = std::move(model_faces);
  st.seconds_faces = since(t0);

  pm.cell_material = std::move(sides.cell_material);
  // Cells name their primal vertex in the input's numbering (what users and
  // files see; ClassifiedTetMesh::input_vertex).
  pm.cell_primal = std::move(sides.cell_vertex);
  for (VertexId& v : pm.cell_primal) v = VertexId(m.input_vertex(v));
  draft.num_cells = sides.num_cells;
  return draft;  // the sides and point maps are freed here, before the cleanup's peak
}

PolyMesh assemble_cells(DualDraft&& draft) {
  PolyMesh pm = std::move(draft.mesh);
  const std::size_t num_cells = draft.num_cells;
  draft = DualDraft{};
  std::vector<std::uint32_t> off(num_cells + 1, 0);
  for (std::size_t f = 0; f < pm.num_faces(); ++f) {
    ++off[pm.face_owner[f].idx + 1];
    if (pm.face_neighbour[f].valid()) ++off[pm.face_neighbour[f].idx + 1];
  }
  for (std::size_t c = 0; c < num_cells; ++c) off[c + 1] += off[c];
  pm.cell_faces.assign(off[num_cells], HalfFace{});
  std::vector<std::uint32_t> fill(off.begin(), off.end() - 1);
  for (std::size_t f = 0; f < pm.num_faces(); ++f) {
    pm.cell_faces[fill[pm.face_owner[f].idx]++] = HalfFace(FaceId(f), 0);
    if (pm.face_neighbour[f].valid()) pm.cell_faces[fill[pm.face_neighbour[f].idx]++] = HalfFace(FaceId(f), 1);
  }
  pm.cell_offsets = std::move(off);
  return pm;
}

PolyMesh build_dual(const ClassifiedTetMesh& m, const DualParams& params, DualStats* stats,
                    const VertexCuts* cuts, const DualScope* scope) {
  DualStats local;
  DualStats& st = stats ? *stats : local;
  st = DualStats{};
  DualDraft draft = build_dual_draft(m, params, &st, cuts, scope);
  // Without hints (params.cleanup off) the cleanup only compacts: it drops
  // faces under 3 distinct points and points no face uses.
  const CleanupStats cs = cleanup_dual(draft);
  st.merged_points = cs.merged_points;
  st.collapsed_points = cs.collapsed_points;
  st.dropped_faces = cs.dropped_faces;
  st.seconds_cleanup = cs.seconds;
  const auto t0 = Clock::now();
  PolyMesh pm = assemble_cells(std::move(draft));
  st.seconds_cells = since(t0);
  return pm;
}

}  // namespace polydual
