// Algorithm 1 on a PrimalMesh (dual/primal_dual.h), step by step as the tet
// builder (dual/build_dual.cpp): points, sides, fan faces, caps, hints; the
// cleanup and the cells are the tet path's own.
#include "dual/primal_dual.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <limits>
#include <span>
#include <map>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "dual/edge_face_blocks.h"
#include "dual/primal_caps.h"
#include "dual/primal_central_points.h"
#include "dual/primal_sides.h"
#include "predicates/predicates.h"

namespace polydual {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Whether edge e / vertex v gets a dual point: on a model edge / at a model
// vertex (the paper), and in keep mode on every model entity (classified in
// dimension <= 2): the rule of build_dual.cpp without cuts.
// A vertex cut whole gives a point to itself and to every edge through it.
bool edge_has_point(const PrimalMesh& m, bool keep, const MixedPoints& d, EdgeId e) {
  return m.edge_class(e).dim == 1 || (keep && m.edge_class(e).dim <= 2) || d.is_whole(m.edge(e)[0]) ||
         d.is_whole(m.edge(e)[1]);
}
bool vertex_has_point(const PrimalMesh& m, bool keep, const MixedPoints& d, VertexId v) {
  return m.vertex_class(v).dim == 0 || (keep && m.vertex_class(v).dim <= 2) || d.is_whole(v);
}
// A face or cell with a vertex cut whole (any_marked of its vertices in
// d.whole) has its vertex mean as central point: a corner of the cell
// between its vertex, the midpoints and the faces' and cell's vertex means is
// convex for a tet, and for any cell whose faces are planar and which is
// convex (the barycentric corner).

// The model faces' central points, in owner_order (primal_caps.h): keep
// mode takes triangle_inner_point for triangles, so the tiles are never
// degenerate; a quadrangle's is its vertex mean either way.
template <class Add>
void add_face_points(const PrimalMesh& m, bool keep, MixedPoints& d, DualStats& st, Add&& add) {
  d.face_pt.assign(m.num_faces(), PointId::invalid());
  d.face_merge.assign(m.num_faces(), 0);
  std::vector<std::pair<std::uint64_t, PrimalFaceId>> model_faces;
  for (std::size_t f = 0; f < m.num_faces(); ++f)
    if (m.face_class(PrimalFaceId(f)).dim == 2) model_faces.emplace_back(owner_order(m, PrimalFaceId(f)), PrimalFaceId(f));
  std::sort(model_faces.begin(), model_faces.end());
  for (const auto& [order, fid] : model_faces) {
    const auto fv = m.face_vertices(fid);
    if (any_marked(fv, d.whole)) {  // a face through a vertex cut whole: its vertex mean
      d.face_pt[fid.idx] = add(vertex_mean(m, fv), m.face_class(fid), 2, fid.idx);
      continue;
    }
    const bool tri = fv.size() == 3;
    bool opposite[3] = {false, false, false};  // the caps' rule (cap_triangle_point)
    for (int k = 0; tri && k < 3; ++k)
      opposite[k] = m.edge_class(m.find_edge(fv[(k + 1) % 3], fv[(k + 2) % 3])).dim <= 1;
    const CentralPoint c = keep && tri ? triangle_inner_point(m.point(fv[0]), m.point(fv[1]), m.point(fv[2]))
                           : tri       ? cap_triangle_point(m.point(fv[0]), m.point(fv[1]), m.point(fv[2]), opposite)
                                       : face_central_point(m, fid);
    d.face_pt[fid.idx] = add(c.p, m.face_class(fid), 2, fid.idx);
    d.face_merge[fid.idx] = char(tri && c.well_centred && !keep);
    if (tri) ++(c.well_centred ? st.well_centred_triangles : st.clamped_triangles);
  }
  if (d.whole.empty()) return;
  for (std::size_t f = 0; f < m.num_faces(); ++f) {  // the other faces through a vertex cut whole
    const PrimalFaceId fid(f);
    const auto fv = m.face_vertices(fid);
    if (!d.face_pt[f].valid() && any_marked(fv, d.whole)) d.face_pt[f] = add(vertex_mean(m, fv), m.face_class(fid), 2, f);
  }
}

// STEP 1-4. Cell centres get PointId == PrimalCellId; then the model faces'
// central points (keep mode: triangle_inner_point for triangles, so the
// tiles are never degenerate; the vertex mean for quadrangles), the edge
// midpoints, the vertices. Central points are rounded constructions; whether
// a tet or triangle holds its circumcentre is decided EXACTLY
// (central_points.h), and only such centres may merge (cleanup hints).
MixedPoints make_points(const PrimalMesh& m, bool keep, const std::vector<char>* whole, PolyMesh& pm,
                        DualStats& st) {
  MixedPoints d;
  if (whole) d.whole = *whole;
  const std::size_t nc = m.num_cells();
  pm.points.resize(nc);
  pm.point_class.resize(nc);
  pm.point_origin.resize(nc);
  d.cell_error.resize(nc);
  // Independent per cell: parallel, the same result for any thread count.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nc, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t c = r.begin(); c < r.end(); ++c) {
      // Tets' and prisms' centres by cell_central_point (circumcentres or
      // clamped, the tet builder's rule; a right prism's circumcentre);
      // another cell's, and every cell's through a vertex cut whole, is its
      // vertex mean (the same rule) without the exact inside test, which
      // nothing here reads (it cost a third of the points stage on a hex block).
      const PrimalCellId cid(c);
      const bool tet = m.cell_type(cid) == CellType::Tet;
      CentralPoint cp{{0, 0, 0}, false, 0};
      if ((tet || m.cell_type(cid) == CellType::Prism) && !any_marked(m.cell_vertices(cid), d.whole))
        cp = cell_central_point(m, cid);
      else
        cp.p = vertex_mean(m, m.cell_vertices(cid));
      pm.points[c] = cp.p;
      pm.point_class[c] = m.cell_class(cid);
      pm.point_origin[c] = PointOrigin{3, std::uint32_t(c)};
      d.cell_error[c] = tet && cp.well_centred ? cp.error : -std::numeric_limits<double>::infinity();
    }
  });
  for (std::size_t c = 0; c < nc; ++c)
    if (m.cell_type(PrimalCellId(c)) == CellType::Tet) ++(d.cell_error[c] >= 0 ? st.well_centred_tets : st.clamped_tets);
  auto add = [&](const Point3& p, ModelRef cls, std::int8_t dim, std::size_t id) {
    pm.points.push_back(p);
    pm.point_class.push_back(cls);
    pm.point_origin.push_back(PointOrigin{dim, std::uint32_t(id)});
    return PointId(pm.points.size() - 1);
  };
  add_face_points(m, keep, d, st, add);
  d.edge_pt.assign(m.num_edges(), PointId::invalid());
  for (std::size_t e = 0; e < m.num_edges(); ++e)
    if (edge_has_point(m, keep, d, EdgeId(e))) {
      const auto ev = m.edge(EdgeId(e));
      d.edge_pt[e] = add(0.5 * (m.point(ev[0]) + m.point(ev[1])), m.edge_class(EdgeId(e)), 1, e);
    }
  d.vert_pt.assign(m.num_vertices(), PointId::invalid());
  for (std::size_t v = 0; v < m.num_vertices(); ++v)
    if (vertex_has_point(m, keep, d, VertexId(v)))
      d.vert_pt[v] = add(m.point(VertexId(v)), m.vertex_class(VertexId(v)), 0, v);
  return d;
}

// The local face of a cell of type t whose outward loop runs from local
// vertex p to q (-1: none): from a cell c around edge (a, b), face
// [p = a][q = b] leads out of c right-handedly about a -> b, [b][a] leads
// back (PrimalMesh::edge_chains' rule, as a table instead of a search).
using LeadTable = std::array<std::array<std::array<std::int8_t, 8>, 8>, 4>;
constexpr LeadTable make_lead_table() {
  LeadTable t{};
  for (auto& type : t)
    for (auto& row : type) row.fill(-1);
  for (int ty = 0; ty < 4; ++ty) {
    const CellDescriptor& d = descriptor(CellType(ty));
    for (int i = 0; i < d.num_faces; ++i)
      for (int k = 0; k < d.face_size[i]; ++k)
        t[ty][d.faces[i][k]][d.faces[i][(k + 1) % d.face_size[i]]] = std::int8_t(i);
  }
  return t;
}
// The same by the edge's code in the cell (PrimalMesh::edge_cell_locals):
// [type][code] = {the face leading out, the face leading back}.
using EdgeLeadTable = std::array<std::array<std::array<std::int8_t, 2>, 24>, 4>;
constexpr EdgeLeadTable make_edge_lead_table() {
  constexpr LeadTable lead = make_lead_table();
  EdgeLeadTable t{};
  for (int ty = 0; ty < 4; ++ty) {
    const CellDescriptor& d = descriptor(CellType(ty));
    for (int k = 0; k < d.num_edges; ++k) {
      const int p = d.edges[k][0], q = d.edges[k][1];
      t[ty][2 * k] = {lead[ty][p][q], lead[ty][q][p]};
      t[ty][2 * k + 1] = {lead[ty][q][p], lead[ty][p][q]};
    }
  }
  return t;
}
constexpr EdgeLeadTable kEdgeLead = make_edge_lead_table();

// The chains of cells around edges (PrimalMesh::edge_chains' chains; a
// closed one may start elsewhere round the edge), walked into reused
// buffers by the cells' positions in edge_cells(e): each step reads the
// faces at e from the edge's code in the cell (a table), not from the
// cell's vertices. The dual's faces stage walks every edge; the allocations
// and face searches of edge_chains() made it 6x slower per element than the
// tet builder's.
struct ChainWalker {
  std::vector<PrimalCellId> cells;
  std::vector<PrimalFaceId> faces;
  std::vector<std::uint32_t> at;  // the positions of cells in edge_cells(e)
  std::vector<char> placed;
  bool closed = false;

  // Calls f() for each chain of e, with cells, faces and closed filled.
  template <class F>
  void for_each_chain(const PrimalMesh& m, EdgeId e, F&& f) {
    const Around r{m.edge_cells(e), m.edge_cell_locals(e)};
    walk(m, r, 0);
    // The common case, one closed chain through every cell round e, needs
    // no record of the cells placed.
    if (closed && cells.size() == r.cells.size()) return f();
    placed.assign(r.cells.size(), 0);
    for (std::size_t i = 0;;) {
      for (std::uint32_t p : at) placed[p] = 1;
      f();
      while (i < r.cells.size() && placed[i]) ++i;
      if (i == r.cells.size()) return;
      walk(m, r, std::uint32_t(i));
    }
  }

 private:
  struct Around {
    std::span<const PrimalCellId> cells;  // increasing
    std::span<const std::uint8_t> codes;
    // The local face of cells[i] leading out (which 0) or back (1) about e.
    int lead(const PrimalMesh& m, std::uint32_t i, int which) const {
      return kEdgeLead[std::size_t(m.cell_type(cells[i]))][codes[i]][which];
    }
    std::uint32_t position(PrimalCellId c) const {
      return std::uint32_t(std::lower_bound(cells.begin(), cells.end(), c) - cells.begin());
    }
  };
  // Forward from position `start`; if the walk comes back to it the chain is
  // closed and starts there (one lap, where PrimalMesh::chain_from walks two
  // and starts a cell later: the same cyclic chain). Otherwise back to the
  // open chain's first cell, then forward from it.
  void walk(const PrimalMesh& m, const Around& r, std::uint32_t start) {
    if (forward(m, r, start)) return;
    std::uint32_t first = start;
    for (;;) {
      const PrimalCellId prev = m.cell_neighbor(r.cells[first], r.lead(m, first, 1));
      if (!prev.valid()) break;
      first = r.position(prev);
    }
    forward(m, r, first);
  }
  bool forward(const PrimalMesh& m, const Around& r, std::uint32_t first) {
    cells.clear();
    faces.clear();
    at.clear();
    const PrimalCellId c0 = r.cells[first];
    faces.push_back(m.cell_face(c0, r.lead(m, first, 1)));
    for (std::uint32_t i = first;;) {
      const PrimalCellId c = r.cells[i];
      cells.push_back(c);
      at.push_back(i);
      const int out = r.lead(m, i, 0);
      faces.push_back(m.cell_face(c, out));
      const PrimalCellId next = m.cell_neighbor(c, out);
      if (!next.valid() || next == c0) {
        closed = next == c0;
        return closed;
      }
      i = r.position(next);
    }
  }
};

// STEP 5-6 for one chain of cells around e = (a, b): the chain is cut at its
// faces on model faces (an open chain also at its end, a boundary face); each
// run of cells between two cuts is one face [centre(start face), cells...,
// centre(end face), midpoint(e) if any], right-handed about a -> b, owned by
// a's side (the fan faces of build_dual.cpp, chain for ring).
void chain_faces(const PrimalMesh& m, const PrimalSides& sides, const MixedPoints& d, EdgeId e, const ChainWalker& ch,
                 PolyMesh& pm, std::vector<std::uint32_t>& scan, std::vector<std::size_t>& cuts,
                 std::vector<PointId>& loop) {
  const VertexId a = m.edge(e)[0], b = m.edge(e)[1];  // not a structured binding: the lambda below captures them
  const std::size_t n = ch.cells.size();
  // An edge through a vertex cut whole is cut at every face (one face per
  // corner); another passes through the points of the faces between its
  // cells that have one (faces through a vertex cut whole).
  const bool whole = d.is_whole(a) || d.is_whole(b);
  cuts.clear();
  // An edge classified in a region has no model face round it.
  const bool may_cut = whole || m.edge_class(e).dim < 3;
  for (std::size_t k = 0; k < n && may_cut; ++k)
    if (whole || m.face_class(ch.faces[k]).dim == 2) cuts.push_back(k);
  if (!ch.closed) cuts.push_back(n);  // faces[n] is the closing boundary face
  auto emit = [&](std::size_t s, std::size_t t, bool bounded) {
    loop.clear();
    const PrimalFaceId start = ch.faces[s], end = ch.faces[t > n ? t - n : t];
    if (bounded) loop.push_back(d.face_pt[start.idx]);
    for (std::size_t k = s; k < t; ++k) {
      if (k > s && d.face_pt[ch.faces[k % n].idx].valid()) loop.push_back(d.face_pt[ch.faces[k % n].idx]);
      loop.push_back(PointId(ch.cells[k % n].idx));
    }
    if (!bounded && d.face_pt[ch.faces[0].idx].valid()) loop.push_back(d.face_pt[ch.faces[0].idx]);
    // One cut on a closed chain (a fracture tip edge): the fan goes all the
    // way round and closes on the start face's centre.
    if (bounded && end != start) {
      loop.push_back(d.face_pt[end.idx]);
      if (d.edge_pt[e.idx].valid()) loop.push_back(d.edge_pt[e.idx]);
    }
    const PrimalCellId c0 = ch.cells[s % n];
    if (bounded) scan.push_back(std::uint32_t(pm.num_faces()));
    pm.add_face(loop, sides.cell(m, c0, a), sides.cell(m, c0, b), FaceKind::Interior, 0);
  };
  if (cuts.empty()) {
    emit(0, n, false);  // an interior chain: closed, no model face
  } else if (!ch.closed) {
    for (std::size_t j = 0; j + 1 < cuts.size(); ++j) emit(cuts[j], cuts[j + 1], true);
  } else {
    for (std::size_t j = 0; j < cuts.size(); ++j) emit(cuts[j], j + 1 < cuts.size() ? cuts[j + 1] : cuts[0] + n, true);
  }
}

// The fan faces of every edge, in edge order (dual/edge_face_blocks.h).
void make_edge_faces(const PrimalMesh& m, const PrimalSides& sides, const MixedPoints& d, PolyMesh& pm,
                     std::vector<std::uint32_t>& scan) {
  make_faces_in_blocks(m.num_edges(), 2048, pm, scan, [&](std::size_t e0, std::size_t e1, EdgeFaceBlock& b) {
    ChainWalker walker;
    std::vector<std::size_t> cuts;
    std::vector<PointId> loop;
    for (std::size_t e = e0; e < e1; ++e)
      walker.for_each_chain(m, EdgeId(e), [&] { chain_faces(m, sides, d, EdgeId(e), walker, b.faces, b.model_faces, cuts, loop); });
  });
}

// The coincidence test adds the two centres' error bounds, widened by 0.1 %
// as in build_dual.cpp (kBoundSlack): too wide costs only an insphere test.
constexpr double kBoundSlack = 1.001;

// The cleanup's hints (build_dual.cpp's point_pairs on a PrimalMesh): across
// each interior face on no model face, the two cell centres closer than
// collapse_length (INEXACT: a length tolerance), and two well-centred tets
// that are cospherical (EXACT insphere == 0, after the error-bound filter).
void cell_pairs(const PrimalMesh& m, const MixedPoints& d, const PolyMesh& pm, double collapse_length,
                DualDraft& draft) {
  const double lim2 = collapse_length * collapse_length;
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    const PrimalCellId c0 = m.face_cell(PrimalFaceId(f), 0), c1 = m.face_cell(PrimalFaceId(f), 1);
    if (!c1.valid() || m.face_class(PrimalFaceId(f)).dim == 2 || d.face_pt[f].valid()) continue;
    const auto [lo, hi] = std::minmax(c0.idx, c1.idx);
    const Vec3 dc = pm.points[hi] - pm.points[lo];
    if (dot(dc, dc) < lim2) draft.short_pairs.emplace_back(PointId(lo), PointId(hi));
    const double tol = kBoundSlack * (d.cell_error[lo] + d.cell_error[hi]);  // -inf unless both well-centred tets
    if (std::fabs(dc.x) > tol || std::fabs(dc.y) > tol || std::fabs(dc.z) > tol) continue;
    const auto a = m.cell_vertices(PrimalCellId(lo)), fv = m.face_vertices(PrimalFaceId(f));
    VertexId far = VertexId::invalid();
    for (VertexId x : m.cell_vertices(PrimalCellId(hi)))
      if (std::find(fv.begin(), fv.end(), x) == fv.end()) far = x;
    if (insphere(m.point(a[0]), m.point(a[1]), m.point(a[2]), m.point(a[3]), m.point(far)) == Sign::Zero)
      draft.exact_pairs.emplace_back(PointId(lo), PointId(hi));
  }
}

// Adjacent well-centred model-face triangles sharing an edge inside their
// model face (class dim 2: exactly two such faces) whose centres coincide:
// EXACT, coplanar (orient3d == 0) and cocircular (insphere with a point off
// the plane == 0), as build_dual.cpp.
void triangle_pairs(const PrimalMesh& m, const MixedPoints& d, DualDraft& draft) {
  struct Rec { std::uint32_t e, f; VertexId opp; };
  std::vector<Rec> recs;
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    if (!d.face_merge[f]) continue;
    const auto tv = m.face_vertices(PrimalFaceId(f));
    for (int k = 0; k < 3; ++k) {
      const EdgeId e = m.find_edge(tv[k], tv[(k + 1) % 3]);
      if (m.edge_class(e).dim == 2) recs.push_back({e.idx, std::uint32_t(f), tv[(k + 2) % 3]});
    }
  }
  std::stable_sort(recs.begin(), recs.end(), [](const Rec& x, const Rec& y) { return x.e < y.e; });
  for (std::size_t k = 0; k + 1 < recs.size(); ++k) {
    if (recs[k].e != recs[k + 1].e) continue;
    const auto t = m.face_vertices(PrimalFaceId(recs[k].f));
    const Point3 &A = m.point(t[0]), &B = m.point(t[1]), &C = m.point(t[2]);
    const Point3& P = m.point(recs[k + 1].opp);
    if (orient3d(A, B, C, P) != Sign::Zero) continue;
    const Point3 E = A + cross(B - A, C - A);
    const Sign o = orient3d(A, B, C, E);
    if (o == Sign::Zero) continue;
    const Sign s = o == Sign::Positive ? insphere(A, B, C, E, P) : insphere(A, C, B, E, P);
    if (s == Sign::Zero) draft.exact_pairs.emplace_back(d.face_pt[recs[k].f], d.face_pt[recs[k + 1].f]);
  }
}

double mean_edge_length(const PrimalMesh& m) {
  double s = 0;
  for (std::size_t e = 0; e < m.num_edges(); ++e) s += norm(m.point(m.edge(EdgeId(e))[1]) - m.point(m.edge(EdgeId(e))[0]));
  return m.num_edges() ? s / double(m.num_edges()) : 0.0;
}

void check_sizes(const PrimalMesh& m) {
  if (m.dim() != 3)
    throw UsageError("build_primal_dual_draft: " + m.source() + " is a surface mesh; the dual needs volume cells");
  if (std::max({m.num_cells(), m.num_faces(), m.num_edges(), m.num_vertices()}) > PointOrigin::kMaxId)
    throw InputError(m.source(), "", "too large for the dual: more than " + std::to_string(PointOrigin::kMaxId) +
                                         " cells, faces, edges or vertices");
}

}  // namespace

std::vector<std::pair<std::int32_t, FaceKind>> primal_face_kinds(const PrimalMesh& m) {
  std::map<std::int32_t, FaceKind> kinds;
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    const PrimalFaceId fid(f);
    if (m.face_class(fid).dim != 2 || kinds.count(m.face_class(fid).tag)) continue;
    const PrimalCellId c0 = m.face_cell(fid, 0), c1 = m.face_cell(fid, 1);
    kinds[m.face_class(fid).tag] = !c1.valid() ? FaceKind::External
                                   : m.cell_class(c0).tag == m.cell_class(c1).tag ? FaceKind::Fracture
                                                                                  : FaceKind::Interface;
  }
  return {kinds.begin(), kinds.end()};
}

double primal_collapse_length(const PrimalMesh& m, const DualParams& params) {
  return params.collapse_tolerance * mean_edge_length(m);
}

DualDraft build_primal_dual_draft(const PrimalMesh& m, const DualParams& params, DualStats* stats,
                                  const std::vector<char>* whole) {
  params.validate();
  check_sizes(m);
  DualStats local;
  DualStats& st = stats ? *stats : local;
  DualDraft draft;
  PolyMesh& pm = draft.mesh;
  const bool keep = params.boundary == BoundaryMode::Keep;
  draft.keep_boundary = keep;
  auto t0 = Clock::now();
  const MixedPoints d = make_points(m, keep, whole, pm, st);
  st.seconds_points = since(t0);
  t0 = Clock::now();
  if (params.cleanup) {
    draft.collapse_length = primal_collapse_length(m, params);
    cell_pairs(m, d, pm, draft.collapse_length, draft);
    triangle_pairs(m, d, draft);
  }
  st.seconds_hints = since(t0);
  t0 = Clock::now();
  PrimalSides sides = compute_primal_sides(m, whole);
  st.seconds_sides = since(t0);
  t0 = Clock::now();
  std::vector<std::uint32_t> scan;
  make_edge_faces(m, sides, d, pm, scan);
  const std::size_t first_cap = pm.num_faces();
  make_primal_caps(m, sides, d, primal_face_kinds(m), keep, pm, st);
  for (std::size_t f = first_cap; f < pm.num_faces(); ++f) scan.push_back(std::uint32_t(f));
  if (params.cleanup) draft.scan_faces = std::move(scan);
  st.seconds_faces = since(t0);
  pm.cell_material = std::move(sides.cell_material);
  // Cells name their primal vertex in the input's numbering.
  pm.cell_primal = std::move(sides.cell_vertex);
  for (VertexId& v : pm.cell_primal) v = VertexId(std::uint32_t(m.input_vertex(v)));
  draft.num_cells = sides.num_cells;
  return draft;
}

PolyMesh build_primal_dual(const PrimalMesh& m, const DualParams& params, DualStats* stats,
                           const std::vector<char>* whole) {
  DualStats local;
  DualStats& st = stats ? *stats : local;
  st = DualStats{};
  DualDraft draft = build_primal_dual_draft(m, params, &st, whole);
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
