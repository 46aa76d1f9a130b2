// The caps of the mixed dual: build_dual.cpp's CapRuns, cap_loop, add_cap,
// keep_cap_faces and touch_vertex on the faces (triangles and quadrangles)
// of a PrimalMesh. A face f through v is seen as (v, A, B): A follows v in
// f's loop, B precedes it (a quadrangle's fourth vertex plays no part).
#include "dual/primal_caps.h"

#include <algorithm>

#include "predicates/predicates.h"

namespace polydual {

std::uint64_t owner_order(const PrimalMesh& m, PrimalFaceId f) {
  const PrimalCellId c = m.face_cell(f, 0);
  int i = 0;
  while (m.cell_face(c, i) != f) ++i;
  return 8 * std::uint64_t(c.idx) + std::uint64_t(i);
}

namespace {

// Vertex -> the faces on model faces through it (CSR, in owner_order).
struct VertexFaces {
  std::vector<std::uint64_t> off;
  std::vector<PrimalFaceId> face;
  std::span<const PrimalFaceId> of(std::size_t v) const { return {face.data() + off[v], face.data() + off[v + 1]}; }
};

VertexFaces vertex_model_faces(const PrimalMesh& m) {
  VertexFaces vf;
  vf.off.assign(m.num_vertices() + 1, 0);
  for (std::size_t f = 0; f < m.num_faces(); ++f)
    if (m.face_class(PrimalFaceId(f)).dim == 2)
      for (VertexId v : m.face_vertices(PrimalFaceId(f))) ++vf.off[v.idx + 1];
  for (std::size_t v = 0; v < m.num_vertices(); ++v) vf.off[v + 1] += vf.off[v];
  vf.face.resize(vf.off.back());
  std::vector<std::uint64_t> fill(vf.off.begin(), vf.off.end() - 1);
  for (std::size_t f = 0; f < m.num_faces(); ++f)
    if (m.face_class(PrimalFaceId(f)).dim == 2)
      for (VertexId v : m.face_vertices(PrimalFaceId(f))) vf.face[fill[v.idx]++] = PrimalFaceId(f);
  std::vector<std::pair<std::uint64_t, PrimalFaceId>> keyed;
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    keyed.clear();
    for (std::uint64_t k = vf.off[v]; k < vf.off[v + 1]; ++k) keyed.emplace_back(owner_order(m, vf.face[k]), vf.face[k]);
    std::sort(keyed.begin(), keyed.end());
    for (std::size_t k = 0; k < keyed.size(); ++k) vf.face[vf.off[v] + k] = keyed[k].second;
  }
  return vf;
}

// The runs of model faces round one vertex v (STEP 7), walked across the
// edges (v, w) that are no model edge (stop edges end a run).
struct Runs {
  struct Oriented { std::uint32_t k; VertexId p, q; };  // face L[k] seen as (v, p, q)
  std::vector<VertexId> A, B;
  std::vector<EdgeId> EA, EB;
  std::vector<char> stopA, stopB, visited;
  std::vector<Oriented> seq;
  std::uint32_t n = 0;

  void load(const PrimalMesh& m, VertexId v, std::span<const PrimalFaceId> L) {
    n = std::uint32_t(L.size());
    A.resize(n), B.resize(n), EA.resize(n), EB.resize(n), stopA.resize(n), stopB.resize(n);
    visited.assign(n, 0);
    for (std::uint32_t k = 0; k < n; ++k) {
      const auto fv = m.face_vertices(L[k]);  // outward from face_cell(L[k], 0)
      const std::size_t s = fv.size(), i = std::size_t(std::find(fv.begin(), fv.end(), v) - fv.begin());
      A[k] = fv[(i + 1) % s];
      B[k] = fv[(i + s - 1) % s];
      EA[k] = m.find_edge(v, A[k]);
      EB[k] = m.find_edge(v, B[k]);
      stopA[k] = m.edge_class(EA[k]).dim == 1;
      stopB[k] = m.edge_class(EB[k]).dim == 1;
    }
  }
  // The run face other than k through (v, w), or -1 at a stop edge.
  std::int64_t across(std::uint32_t k, VertexId w) const {
    if (w == A[k] ? stopA[k] : stopB[k]) return -1;
    for (std::uint32_t j = 0; j < n; ++j)
      if (j != k && (A[j] == w || B[j] == w)) return j;
    return -1;
  }
  VertexId other_than(std::uint32_t j, VertexId w) const { return A[j] == w ? B[j] : A[j]; }
  EdgeId edge_to(std::uint32_t j, VertexId w) const { return A[j] == w ? EA[j] : EB[j]; }

  // The run through face i0 into seq (from its start if open); whether it is closed.
  bool walk(std::uint32_t i0) {
    const Oriented first{i0, A[i0], B[i0]};
    Oriented start = first;
    bool closed = false;
    for (;;) {
      const std::int64_t g = across(start.k, start.p);
      if (g < 0) break;
      if (std::uint32_t(g) == first.k) { closed = true; break; }
      start = Oriented{std::uint32_t(g), other_than(std::uint32_t(g), start.p), start.p};
    }
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

// The loop of the cap of runs.seq round v; true when the run leaves and
// re-enters through one model edge (a pole on a seam), see add_cap.
bool cap_loop(const MixedPoints& d, VertexId v, std::span<const PrimalFaceId> L, const Runs& runs, bool closed,
              std::vector<PointId>& loop) {
  const auto& seq = runs.seq;
  loop.clear();
  if (!closed) loop.push_back(d.edge_pt[runs.edge_to(seq.front().k, seq.front().p).idx]);
  for (std::size_t i = 0; i < seq.size(); ++i) {
    loop.push_back(d.face_pt[L[seq[i].k].idx]);
    // An edge inside the run with a point (to a vertex cut whole): the
    // neighbouring corners' walls end there.
    if (i + 1 < seq.size() || closed)
      if (const PointId e = d.edge_pt[runs.edge_to(seq[i].k, seq[i].q).idx]; e.valid()) loop.push_back(e);
  }
  if (closed) return false;
  if (seq.front().p == seq.back().q) return true;
  loop.push_back(d.edge_pt[runs.edge_to(seq.back().k, seq.back().q).idx]);
  if (d.vert_pt[v.idx].valid()) loop.push_back(d.vert_pt[v.idx]);
  return false;
}

// build_dual.cpp's add_cap: one face, or two through v's point when the loop
// winds round the model vertex v (proofs/dual_invariants.md L1).
void add_cap(PolyMesh& pm, const std::vector<PointId>& loop, bool round_v, PointId v_point, CellId owner,
             CellId neigh, FaceKind kind, std::int32_t tag) {
  const std::size_t k = loop.size() - 1;
  if (!round_v || !v_point.valid() || k < 2) {
    pm.add_face(loop, owner, neigh, kind, tag);
    return;
  }
  const std::size_t j = (k + 1) / 2;
  std::vector<PointId> a{v_point}, b{v_point};
  a.insert(a.end(), loop.begin(), loop.begin() + static_cast<std::ptrdiff_t>(j + 1));
  b.insert(b.end(), loop.begin() + static_cast<std::ptrdiff_t>(j), loop.end());
  b.push_back(loop.front());
  pm.add_face(a, owner, neigh, kind, tag);
  pm.add_face(b, owner, neigh, kind, tag);
}

// build_dual.cpp's keep_cap_faces: the tiles (v, mid(v p), centre(f), mid(v q))
// of the run's faces, consecutive ones merged while coplanar (EXACT orient3d
// of v, p, q and the next face's q). A quadrangle's tile is planar when the
// quadrangle is (its centre is the mean of its vertices).
void keep_cap_faces(const PrimalMesh& m, const MixedPoints& d, VertexId v, std::span<const PrimalFaceId> L,
                    const Runs& runs, bool closed, bool touch, std::vector<std::vector<PointId>>& faces) {
  const auto& seq = runs.seq;
  const std::size_t n = seq.size();
  faces.clear();
  auto mid = [&](std::size_t i, VertexId w) { return d.edge_pt[runs.edge_to(seq[i].k, w).idx]; };
  auto centre = [&](std::size_t i) { return d.face_pt[L[seq[i].k].idx]; };
  std::vector<char> starts(n, 0);
  std::size_t num_starts = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (i == 0 && !closed) { starts[0] = 1; ++num_starts; continue; }
    const auto& a = seq[(i + n - 1) % n];
    starts[i] = char(orient3d(m.point(v), m.point(a.p), m.point(a.q), m.point(seq[i].q)) != Sign::Zero);
    num_starts += starts[i];
  }
  if (closed && num_starts == 0 && touch && n >= 2) starts[0] = starts[n / 2] = 1;
  else if (closed && num_starts == 0) {
    faces.emplace_back();
    for (std::size_t i = 0; i < n; ++i) {
      faces.back().push_back(mid(i, seq[i].p));
      faces.back().push_back(centre(i));
    }
    return;
  }
  if (!closed && num_starts == 1 && seq.front().p == seq.back().q) starts[n / 2] = 1;
  std::size_t first = 0;
  while (!starts[first]) ++first;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = (first + k) % n;
    if (starts[i]) faces.push_back({d.vert_pt[v.idx], mid(i, seq[i].p)});
    faces.back().push_back(centre(i));
    faces.back().push_back(mid(i, seq[i].q));
  }
}

// A model vertex with a point where no run stops (model faces touching
// without a model edge): every run round it is cut in two there.
bool touch_vertex(const PrimalMesh& m, const MixedPoints& d, VertexId v, const Runs& runs) {
  if (m.vertex_class(v).dim != 0 || !d.vert_pt[v.idx].valid()) return false;
  for (std::uint32_t k = 0; k < runs.n; ++k)
    if (runs.stopA[k] || runs.stopB[k]) return false;
  return true;
}

FaceKind kind_of(const std::vector<std::pair<std::int32_t, FaceKind>>& kinds, std::int32_t tag) {
  const auto it = std::lower_bound(kinds.begin(), kinds.end(), tag,
                                   [](const std::pair<std::int32_t, FaceKind>& k, std::int32_t t) { return k.first < t; });
  return it->second;
}

// The walls of the corners of a vertex v cut whole: per face through v, the
// tile (v, mid(v A), centre, mid(v B)) in the face's outward order (A after
// v in its loop, B before), between the corners of its two cells (one on the
// boundary).
void whole_tiles(const PrimalMesh& m, const PrimalSides& sides, const MixedPoints& d,
                 const std::vector<std::pair<std::int32_t, FaceKind>>& kinds, VertexId v, PolyMesh& pm) {
  std::vector<PrimalFaceId> faces;
  for (PrimalCellId c : m.vertex_cells(v)) {
    const CellDescriptor& desc = m.cell_descriptor(c);
    for (int i = 0; i < desc.num_faces; ++i) {
      const PrimalFaceId f = m.cell_face(c, i);
      const auto fv = m.face_vertices(f);
      if (std::find(fv.begin(), fv.end(), v) != fv.end() && m.face_cell(f, 0) == c) faces.push_back(f);
    }
  }
  std::sort(faces.begin(), faces.end());
  for (PrimalFaceId f : faces) {
    const auto fv = m.face_vertices(f);
    const std::size_t s = fv.size(), i = std::size_t(std::find(fv.begin(), fv.end(), v) - fv.begin());
    const PointId a = d.edge_pt[m.find_edge(v, fv[(i + 1) % s]).idx], b = d.edge_pt[m.find_edge(v, fv[(i + s - 1) % s]).idx];
    const PrimalCellId c0 = m.face_cell(f, 0), c1 = m.face_cell(f, 1);
    const CellId owner = sides.cell(m, c0, v), neigh = c1.valid() ? sides.cell(m, c1, v) : CellId::invalid();
    const bool model = m.face_class(f).dim == 2;
    const std::int32_t tag = model ? m.face_class(f).tag : 0;
    const PointId tile[4] = {d.vert_pt[v.idx], a, d.face_pt[f.idx], b};
    pm.add_face(tile, owner, neigh, model ? kind_of(kinds, tag) : FaceKind::Interior, tag);
  }
}

}  // namespace

void make_primal_caps(const PrimalMesh& m, const PrimalSides& sides, const MixedPoints& d,
                      const std::vector<std::pair<std::int32_t, FaceKind>>& kinds, bool keep, PolyMesh& pm,
                      DualStats& st) {
  for (std::size_t vi = 0; vi < m.num_vertices(); ++vi)
    if (d.is_whole(VertexId(vi))) whole_tiles(m, sides, d, kinds, VertexId(vi), pm);
  const VertexFaces vf = vertex_model_faces(m);
  Runs runs;
  std::vector<PointId> loop;
  std::vector<std::vector<PointId>> tiles;
  for (std::size_t vi = 0; vi < m.num_vertices(); ++vi) {
    const VertexId v(vi);
    const auto L = vf.of(vi);
    if (L.empty() || d.is_whole(v)) continue;
    runs.load(m, v, L);
    const bool touch = touch_vertex(m, d, v, runs);
    for (std::uint32_t i0 = 0; i0 < runs.n; ++i0) {
      if (runs.visited[i0]) continue;
      const bool closed = runs.walk(i0);
      const bool round_v = !keep && (cap_loop(d, v, L, runs, closed, loop) || (closed && touch));
      if (keep) keep_cap_faces(m, d, v, L, runs, closed, touch, tiles);
      // The loop follows L[i0]'s orientation (every face of the walk
      // inherits it): the owner is the side of the cell it points out of.
      const PrimalFaceId f0 = L[i0];
      const PrimalCellId c0 = m.face_cell(f0, 0), c1 = m.face_cell(f0, 1);
      const CellId owner = sides.cell(m, c0, v);
      const CellId neigh = c1.valid() ? sides.cell(m, c1, v) : CellId::invalid();
      if (owner == neigh) ++st.slit_faces;
      const std::int32_t tag = m.face_class(f0).tag;
      if (keep)
        for (const auto& tile : tiles) pm.add_face(tile, owner, neigh, kind_of(kinds, tag), tag);
      else
        add_cap(pm, loop, round_v, d.vert_pt[v.idx], owner, neigh, kind_of(kinds, tag), tag);
    }
  }
}

}  // namespace polydual
