#include "split/split.h"

#include <CGAL/Gmpzf.h>
#include <CGAL/QP_functions.h>
#include <CGAL/QP_models.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <string>

#include "core/error.h"
#include "core/stopwatch.h"
#include "predicates/predicates.h"

namespace polydual {

void SplitParams::validate() const {
  if (max_groups < 1 || max_groups > kMaxGroups)
    throw UsageError("split max groups " + std::to_string(max_groups) + " is outside [1, " +
                     std::to_string(kMaxGroups) + "]");
}

Json SplitParams::to_json() const {
  Json j = Json::object();
  j.set("enabled", enabled);
  j.set("max_groups", max_groups);
  j.set("merge", merge);
  return j;
}

Json SplitStats::to_json() const {
  Json j = Json::object();
  j.set("cells_split", cells_split);
  j.set("pieces", pieces);
  j.set("failed", failed);
  j.set("new_points", new_points);
  j.set("new_faces", new_faces);
  j.set("one_group", one_group);
  j.set("lp_solves", lp_solves);
  j.set("seconds", seconds);
  return j;
}

namespace {

Point3 sub(const Point3& a, const Point3& b) { return a - b; }

// One half-space n.X + t <= rhs of a max-margin LP (n unit, or zero: t <= rhs).
struct HalfSpace {
  Point3 n;
  double rhs;
};
// The half-space n.(X - on) < 0, normalised (a zero n gives t <= 0: infeasible).
HalfSpace unit_half_space(const Point3& n, const Point3& on) {
  const double len = std::sqrt(dot(n, n));
  if (!(len > 0)) return {{0, 0, 0}, 0};
  const Point3 u{n.x / len, n.y / len, n.z / len};
  return {u, dot(u, on)};
}

struct Box {
  Point3 lo, hi;
};

// The point X of the box maximising t subject to n_i.X + t <= rhs_i (CGAL's
// exact QP solver on Gmpzf); nullopt when the best margin is not positive.
// The LP only places points: every sign is decided afterwards by the exact
// star test of the pieces.
std::optional<Point3> deepest_point(std::span<const HalfSpace> hs, const Box& box, std::size_t& solves) {
  ++solves;
  CGAL::Quadratic_program<double> lp(CGAL::SMALLER, false, 0, false, 0);
  for (int i = 0; i < static_cast<int>(hs.size()); ++i) {
    lp.set_a(0, i, hs[i].n.x);
    lp.set_a(1, i, hs[i].n.y);
    lp.set_a(2, i, hs[i].n.z);
    lp.set_a(3, i, 1.0);
    lp.set_b(i, hs[i].rhs);
  }
  const double lo[3] = {box.lo.x, box.lo.y, box.lo.z}, hi[3] = {box.hi.x, box.hi.y, box.hi.z};
  for (int j = 0; j < 3; ++j) {
    lp.set_l(j, true, lo[j]);
    lp.set_u(j, true, hi[j]);
  }
  const Point3 d = sub(box.hi, box.lo);
  lp.set_u(3, true, std::sqrt(dot(d, d)));
  lp.set_c(3, -1.0);
  const auto s = CGAL::solve_linear_program(lp, CGAL::Gmpzf());
  if (!s.is_optimal()) return std::nullopt;
  double v[4];
  auto it = s.variable_values_begin();
  for (int j = 0; j < 4; ++j, ++it) v[j] = CGAL::to_double(*it);
  // A margin below ~1e-9 of the cell size would not survive the rounding of X.
  if (!(v[3] > 1e-9 * std::sqrt(dot(d, d)))) return std::nullopt;
  return Point3{v[0], v[1], v[2]};
}

// The cell as loops of its half-faces, in its outward order.
struct CellLoops {
  std::vector<HalfFace> halves;
  std::vector<std::vector<PointId>> loops;
  std::vector<Point3> centres;  // F of each loop (rounded mean; the LP only)
  Box box;
};

CellLoops cell_loops(const PolyMesh& m, CellId c) {
  CellLoops cl;
  cl.box = {{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
  for (HalfFace h : m.cell(c)) {
    cl.halves.push_back(h);
    cl.loops.push_back(m.oriented_loop(h));
    Point3 s{0, 0, 0};
    for (PointId p : cl.loops.back()) {
      const Point3& q = m.points[p.idx];
      s = {s.x + q.x, s.y + q.y, s.z + q.z};
      cl.box.lo = {std::min(cl.box.lo.x, q.x), std::min(cl.box.lo.y, q.y), std::min(cl.box.lo.z, q.z)};
      cl.box.hi = {std::max(cl.box.hi.x, q.x), std::max(cl.box.hi.y, q.y), std::max(cl.box.hi.z, q.z)};
    }
    const double k = static_cast<double>(cl.loops.back().size());
    cl.centres.push_back({s.x / k, s.y / k, s.z / k});
  }
  return cl;
}

// The inner cone of a loop: X with det[a-F, b-F, X-F] < 0 for every edge (a,b)
// (split.md L1: then cone(loop, X) passes the star test).
void append_cone(const PolyMesh& m, const CellLoops& cl, std::size_t i, std::vector<HalfSpace>& hs) {
  const auto& loop = cl.loops[i];
  const Point3& F = cl.centres[i];
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const Point3 a = sub(m.points[loop[k].idx], F), b = sub(m.points[loop[(k + 1) % loop.size()].idx], F);
    hs.push_back(unit_half_space(cross(a, b), F));
  }
}

// Greedy grouping of the half-faces in `order`: each joins the first group whose
// cones it shares a deep point with, else opens a new group.
struct Grouping {
  std::vector<int> group_of;     // per half-face
  std::vector<Point3> apex;      // per group
};
std::optional<Grouping> group_half_faces(const PolyMesh& m, const CellLoops& cl, std::span<const std::size_t> order,
                                         int max_groups, std::size_t& solves) {
  Grouping g;
  g.group_of.assign(cl.loops.size(), -1);
  std::vector<std::vector<HalfSpace>> cones;
  for (std::size_t i : order) {
    bool placed = false;
    for (std::size_t k = 0; k < cones.size() && !placed; ++k) {
      std::vector<HalfSpace> trial = cones[k];
      append_cone(m, cl, i, trial);
      if (auto x = deepest_point(trial, cl.box, solves)) {
        cones[k] = std::move(trial);
        g.apex[k] = *x;
        g.group_of[i] = static_cast<int>(k);
        placed = true;
      }
    }
    if (placed) continue;
    if (static_cast<int>(cones.size()) == max_groups) return std::nullopt;
    std::vector<HalfSpace> own;
    append_cone(m, cl, i, own);
    auto x = deepest_point(own, cl.box, solves);
    if (!x) return std::nullopt;  // the half-face's own cone is empty
    cones.push_back(std::move(own));
    g.apex.push_back(*x);
    g.group_of[i] = static_cast<int>(cones.size() - 1);
  }
  return g;
}


// A piece as its half-faces of the cell and its new triangles (outward order).
using Tri = std::array<PointId, 3>;
struct Piece {
  std::vector<HalfFace> halves;
  std::vector<Tri> tris;
};

// Unordered key of a triangle and whether t is in the key's orientation.
std::pair<std::array<std::uint32_t, 3>, bool> tri_key(const Tri& t) {
  int r = 0;
  for (int k = 1; k < 3; ++k)
    if (t[k].idx < t[r].idx) r = k;
  const std::uint32_t a = t[r].idx, b = t[(r + 1) % 3].idx, c = t[(r + 2) % 3].idx;
  return {{a, std::min(b, c), std::max(b, c)}, b < c};
}

// The exact star test (quality/star_verdict.h) of a piece not yet in the mesh.
bool piece_valid(const PolyMesh& m, const Piece& piece) {
  std::vector<std::vector<PointId>> loops;
  for (HalfFace h : piece.halves) loops.push_back(m.oriented_loop(h));
  for (const Tri& t : piece.tris) loops.push_back({t[0], t[1], t[2]});
  std::vector<PointId> ids;
  for (const auto& l : loops) ids.insert(ids.end(), l.begin(), l.end());
  std::sort(ids.begin(), ids.end(), [](PointId a, PointId b) { return a.idx < b.idx; });
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  std::vector<Point3> cell_pts, face_pts;
  for (PointId p : ids) cell_pts.push_back(m.points[p.idx]);
  for (const auto& l : loops) {
    face_pts.clear();
    for (PointId p : l) face_pts.push_back(m.points[p.idx]);
    for (std::size_t k = 0; k < l.size(); ++k)
      if (decomposition_tet_sign(m.points[l[k].idx], m.points[l[(k + 1) % l.size()].idx], face_pts, cell_pts) !=
          Sign::Positive)
        return false;
  }
  return true;
}

// The union of pieces: their half-faces, and their triangles less the pairs
// of opposite copies (the faces between them).
Piece merge_pieces(std::span<const Piece> parts) {
  Piece out;
  std::map<std::array<std::uint32_t, 3>, std::array<std::vector<Tri>, 2>> by_key;
  for (const Piece& p : parts) {
    out.halves.insert(out.halves.end(), p.halves.begin(), p.halves.end());
    for (const Tri& t : p.tris) {
      auto [key, pos] = tri_key(t);
      by_key[key][pos ? 0 : 1].push_back(t);
    }
  }
  for (auto& [key, sides] : by_key) {
    const std::size_t common = std::min(sides[0].size(), sides[1].size());
    for (int s = 0; s < 2; ++s)
      out.tris.insert(out.tris.end(), sides[s].begin() + static_cast<std::ptrdiff_t>(common), sides[s].end());
  }
  return out;
}

// The net boundary chain of each group (edge uses p->q that no other half-face
// of the group cancels), as (p, q, group).
struct CoreUse {
  PointId p, q;
  int group;
};
std::vector<CoreUse> core_uses(const CellLoops& cl, const Grouping& g) {
  std::vector<CoreUse> uses;
  const int groups = static_cast<int>(g.apex.size());
  for (int k = 0; k < groups; ++k) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> net;
    for (std::size_t i = 0; i < cl.loops.size(); ++i) {
      if (g.group_of[i] != k) continue;
      const auto& l = cl.loops[i];
      for (std::size_t e = 0; e < l.size(); ++e) {
        const std::uint32_t a = l[e].idx, b = l[(e + 1) % l.size()].idx;
        net[{std::min(a, b), std::max(a, b)}] += a < b ? 1 : -1;
      }
    }
    for (const auto& [edge, n] : net)
      for (int r = 0; r < std::abs(n); ++r)
        uses.push_back(n > 0 ? CoreUse{PointId(edge.first), PointId(edge.second), k}
                             : CoreUse{PointId(edge.second), PointId(edge.first), k});
  }
  return uses;
}

// The pyramids cone(f, X_g) and the core tets (p, X_g, q, Y) of one grouping
// (split.md, construction); apex[k] and core are point ids already in m.
std::vector<Piece> initial_pieces(const CellLoops& cl, const Grouping& g, std::span<const PointId> apex,
                                  std::span<const CoreUse> uses, PointId core) {
  std::vector<Piece> pieces;
  for (std::size_t i = 0; i < cl.loops.size(); ++i) {
    Piece p;
    p.halves.push_back(cl.halves[i]);
    const auto& l = cl.loops[i];
    const PointId x = apex[static_cast<std::size_t>(g.group_of[i])];
    for (std::size_t e = 0; e < l.size(); ++e) p.tris.push_back({l[(e + 1) % l.size()], l[e], x});
    pieces.push_back(std::move(p));
  }
  for (const CoreUse& u : uses) {
    const PointId x = apex[static_cast<std::size_t>(u.group)];
    pieces.push_back(Piece{{}, {Tri{u.p, u.q, x}, Tri{x, u.q, core}, Tri{u.p, core, u.q}, Tri{u.p, x, core}}});
  }
  return pieces;
}

// Replaces the pyramids and core tets of each group by their union (the
// group's half-faces closed by the cut triangles (p, Y, q)) where the union
// passes the exact test. Pieces 0..halves-1 are the pyramids.
std::vector<Piece> merged_pieces(const PolyMesh& m, std::vector<Piece> pieces, const Grouping& g,
                                 std::size_t num_halves, std::span<const CoreUse> uses) {
  std::vector<int> core_group;
  for (const CoreUse& u : uses) core_group.push_back(u.group);
  const int groups = static_cast<int>(g.apex.size());
  std::vector<Piece> out;
  std::vector<std::vector<Piece>> classes(static_cast<std::size_t>(groups));
  for (std::size_t i = 0; i < pieces.size(); ++i)
    classes[i < num_halves ? static_cast<std::size_t>(g.group_of[i]) : static_cast<std::size_t>(core_group[i - num_halves])]
        .push_back(std::move(pieces[i]));
  for (auto& cls : classes) {
    if (cls.size() > 1) {
      Piece u = merge_pieces(cls);
      if (piece_valid(m, u)) {
        out.push_back(std::move(u));
        continue;
      }
    }
    for (Piece& p : cls) out.push_back(std::move(p));
  }
  return out;
}

// A new face between two pieces: its loop (outward for `owner`).
struct NewFace {
  Tri loop;
  std::size_t owner, neighbour;  // piece indices
};
// Pairs the pieces' triangles into faces; nullopt if some triangle has no
// opposite copy in another piece (a construction error guard).
std::optional<std::vector<NewFace>> pair_triangles(std::span<const Piece> pieces) {
  std::map<std::array<std::uint32_t, 3>, std::array<std::vector<std::pair<std::size_t, Tri>>, 2>> by_key;
  for (std::size_t i = 0; i < pieces.size(); ++i)
    for (const Tri& t : pieces[i].tris) {
      auto [key, pos] = tri_key(t);
      by_key[key][pos ? 0 : 1].push_back({i, t});
    }
  std::vector<NewFace> faces;
  for (const auto& [key, sides] : by_key) {
    if (sides[0].size() != sides[1].size()) return std::nullopt;
    for (std::size_t k = 0; k < sides[0].size(); ++k) {
      if (sides[0][k].first == sides[1][k].first) return std::nullopt;
      faces.push_back({sides[0][k].second, sides[0][k].first, sides[1][k].first});
    }
  }
  return faces;
}

}  // namespace

namespace {

// A checked plan for one cell: its final pieces and the faces between them.
// Its new points are already appended to the mesh (removed again on failure).
struct Plan {
  std::vector<Piece> pieces;
  std::vector<NewFace> faces;
  bool one_group = false;
};

// With the core point fixed at y, moves each apex X_g to the deepest point of
// its cones and of the half-spaces det[X_g - p, q - p, y - p] > 0 of its core
// uses (both linear in X_g). false when some group has no such point.
bool replace_apexes(PolyMesh& m, const CellLoops& cl, const Grouping& g, std::span<const CoreUse> uses,
                    const Point3& y, std::span<const PointId> apex, std::size_t& solves) {
  for (std::size_t k = 0; k < apex.size(); ++k) {
    std::vector<HalfSpace> hs;
    for (std::size_t i = 0; i < cl.loops.size(); ++i)
      if (g.group_of[i] == static_cast<int>(k)) append_cone(m, cl, i, hs);
    for (const CoreUse& u : uses) {
      if (u.group != static_cast<int>(k)) continue;
      const Point3& p = m.points[u.p.idx];
      const Point3 n = cross(m.points[u.q.idx] - p, y - p);
      hs.push_back(unit_half_space(-1.0 * n, p));
    }
    const auto x = deepest_point(hs, cl.box, solves);
    if (!x) return false;
    m.points[apex[k].idx] = *x;
  }
  return true;
}

// Apex points, core point and pieces for one grouping; nullopt (points
// removed) when the core point has no deep position or a piece fails the
// exact test.
std::optional<Plan> plan_for_grouping(PolyMesh& m, const CellLoops& cl, const Grouping& g, std::int32_t material,
                                      const SplitParams& params, std::size_t& solves) {
  const std::size_t np0 = m.points.size();
  const ModelRef region{3, material};
  std::vector<PointId> apex;
  for (const Point3& x : g.apex) apex.push_back(m.add_point(x, region));
  const std::vector<CoreUse> uses = core_uses(cl, g);
  PointId core;
  auto rollback = [&] {
    m.points.resize(np0);
    m.point_class.resize(np0);
    return std::nullopt;
  };
  if (!uses.empty()) {
    // Y strictly on the inner side of every core tet's base (p, X_g, q).
    std::vector<HalfSpace> hs;
    for (const CoreUse& u : uses) {
      const Point3& p = m.points[u.p.idx];
      const Point3 n = cross(sub(m.points[apex[static_cast<std::size_t>(u.group)].idx], p), sub(m.points[u.q.idx], p));
      hs.push_back(unit_half_space({-n.x, -n.y, -n.z}, p));
    }
    auto y = deepest_point(hs, cl.box, solves);
    if (!y) {
      // Fix Y at the mean of the chain's points; the core constraints are then
      // linear in each apex: re-place every apex with them.
      Point3 mean{0, 0, 0};
      for (const CoreUse& u : uses) mean += m.points[u.p.idx];
      mean = mean / static_cast<double>(uses.size());
      if (replace_apexes(m, cl, g, uses, mean, apex, solves)) y = mean;
    }
    if (!y) return rollback();
    core = m.add_point(*y, region);
  }
  std::vector<Piece> pieces = initial_pieces(cl, g, apex, uses, core);
  for (const Piece& p : pieces)
    if (!piece_valid(m, p)) return rollback();
  if (params.merge) pieces = merged_pieces(m, std::move(pieces), g, cl.loops.size(), uses);
  auto faces = pair_triangles(pieces);
  if (!faces) return rollback();
  return Plan{std::move(pieces), std::move(*faces), g.apex.size() == 1};
}

// Newell normal of a loop (twice its vector area).
Point3 loop_normal(const PolyMesh& m, const std::vector<PointId>& l) {
  Point3 n{0, 0, 0};
  for (std::size_t k = 0; k < l.size(); ++k)
    n += cross(m.points[l[k].idx], m.points[l[(k + 1) % l.size()].idx]);
  return n;
}

// For a slit cell (both half-faces of a face f in the cell): the half-faces
// on either side of f's plane, each side with the half of f that faces it,
// each side grouped greedily in turn. The two sides meet along the cone cut
// from the core point over their common chain. nullopt when the cell has no
// slit face.
std::optional<Grouping> slit_grouping(const PolyMesh& m, const CellLoops& cl, int max_groups, std::size_t& solves) {
  std::size_t slit = cl.halves.size();
  for (std::size_t i = 0; i < cl.halves.size() && slit == cl.halves.size(); ++i)
    for (std::size_t j = 0; j < cl.halves.size(); ++j)
      if (j != i && cl.halves[j].face() == cl.halves[i].face()) slit = i;
  if (slit == cl.halves.size()) return std::nullopt;
  const Point3 n = loop_normal(m, cl.loops[slit]), F = cl.centres[slit];
  std::vector<std::size_t> side[2];
  for (std::size_t i = 0; i < cl.halves.size(); ++i) {
    double s;
    if (cl.halves[i].face() == cl.halves[slit].face())
      s = -dot(loop_normal(m, cl.loops[i]), n);  // the cell lies against the outward normal
    else
      s = dot(cl.centres[i] - F, n);
    side[s > 0 ? 0 : 1].push_back(i);
  }
  Grouping out;
  out.group_of.assign(cl.halves.size(), -1);
  for (const auto& half : side) {
    const auto g = group_half_faces(m, cl, half, max_groups - static_cast<int>(out.apex.size()), solves);
    if (!g) return std::nullopt;
    const int base = static_cast<int>(out.apex.size());
    for (std::size_t i : half) out.group_of[i] = base + g->group_of[i];
    out.apex.insert(out.apex.end(), g->apex.begin(), g->apex.end());
  }
  return out;
}

// Tries the groupings of the half-faces in a few orders (cell order, largest
// loops first, reversed); the first whose pieces all pass wins.
std::optional<Plan> plan_cell(PolyMesh& m, CellId c, const SplitParams& params, std::size_t& solves) {
  const CellLoops cl = cell_loops(m, c);
  const std::size_t n = cl.loops.size();
  std::vector<std::vector<std::size_t>> orders(3, std::vector<std::size_t>(n));
  for (std::size_t i = 0; i < n; ++i) orders[0][i] = orders[1][i] = orders[2][n - 1 - i] = i;
  std::stable_sort(orders[1].begin(), orders[1].end(),
                   [&](std::size_t a, std::size_t b) { return cl.loops[a].size() > cl.loops[b].size(); });
  std::vector<std::optional<Grouping>> groupings;
  if (auto g = slit_grouping(m, cl, params.max_groups, solves)) groupings.push_back(std::move(g));
  for (const auto& order : orders) groupings.push_back(group_half_faces(m, cl, order, params.max_groups, solves));
  for (const auto& g : groupings) {
    if (!g) continue;
    if (auto plan = plan_for_grouping(m, cl, *g, m.cell_material[c.idx], params, solves)) return plan;
  }
  return std::nullopt;
}

// The cells' new half-face lists, kept until the CSR is rebuilt once.
struct Rebuild {
  std::map<std::uint32_t, std::vector<HalfFace>> replaced;  // split cell -> piece 0
  std::vector<std::vector<HalfFace>> appended;              // other pieces
  std::vector<CellId> appended_origin;
};

// Writes a checked plan into the mesh: owner/neighbour of the cell's faces,
// the new faces, the pieces' half-face lists.
void apply_plan(PolyMesh& m, CellId c, const Plan& plan, Rebuild& rb) {
  const std::size_t base = m.num_cells();
  std::vector<CellId> id(plan.pieces.size());
  std::vector<std::vector<HalfFace>> lists(plan.pieces.size());
  for (std::size_t k = 0; k < plan.pieces.size(); ++k)
    id[k] = k == 0 ? c : CellId(base + rb.appended.size() + k - 1);
  for (std::size_t k = 0; k < plan.pieces.size(); ++k)
    for (HalfFace h : plan.pieces[k].halves) {
      (h.side() == 0 ? m.face_owner : m.face_neighbour)[h.face().idx] = id[k];
      lists[k].push_back(h);
    }
  for (const NewFace& f : plan.faces) {
    const FaceId nf = m.add_face(f.loop, id[f.owner], id[f.neighbour], FaceKind::Interior, 0);
    lists[f.owner].push_back(HalfFace(nf, 0));
    lists[f.neighbour].push_back(HalfFace(nf, 1));
  }
  rb.replaced[c.idx] = std::move(lists[0]);
  for (std::size_t k = 1; k < lists.size(); ++k) {
    rb.appended.push_back(std::move(lists[k]));
    rb.appended_origin.push_back(c);
  }
}

void rebuild_cells(PolyMesh& m, const Rebuild& rb) {
  const std::size_t n = m.num_cells();
  std::vector<std::uint32_t> offsets{0};
  std::vector<HalfFace> faces;
  faces.reserve(m.cell_faces.size() + 8 * rb.appended.size());
  for (std::size_t c = 0; c < n; ++c) {
    const auto it = rb.replaced.find(static_cast<std::uint32_t>(c));
    if (it != rb.replaced.end()) faces.insert(faces.end(), it->second.begin(), it->second.end());
    else {
      const auto old = m.cell(CellId(c));
      faces.insert(faces.end(), old.begin(), old.end());
    }
    offsets.push_back(static_cast<std::uint32_t>(faces.size()));
  }
  for (std::size_t k = 0; k < rb.appended.size(); ++k) {
    faces.insert(faces.end(), rb.appended[k].begin(), rb.appended[k].end());
    offsets.push_back(static_cast<std::uint32_t>(faces.size()));
    const CellId o = rb.appended_origin[k];
    m.cell_material.push_back(m.cell_material[o.idx]);
    m.cell_primal.push_back(m.cell_primal[o.idx]);
    m.cell_origin.push_back(m.cell_origin[o.idx]);
  }
  m.cell_offsets = std::move(offsets);
  m.cell_faces = std::move(faces);
}

}  // namespace

SplitStats split_cells(PolyMesh& mesh, std::span<const CellId> cells, const SplitParams& params) {
  params.validate();
  const Stopwatch clock;
  SplitStats st;
  if (mesh.cell_origin.empty())
    for (std::size_t c = 0; c < mesh.num_cells(); ++c) mesh.cell_origin.push_back(CellId(c));
  const std::size_t np0 = mesh.num_points(), nf0 = mesh.num_faces();
  Rebuild rb;
  std::vector<bool> seen(mesh.num_cells(), false);
  for (CellId c : cells) {
    if (c.idx >= mesh.num_cells()) throw UsageError("split: cell " + std::to_string(c.idx) + " does not exist");
    if (seen[c.idx]) continue;
    seen[c.idx] = true;
    auto plan = plan_cell(mesh, c, params, st.lp_solves);
    if (!plan) {
      ++st.failed;
      st.failed_cells.push_back(c);
      continue;
    }
    ++st.cells_split;
    st.pieces += plan->pieces.size();
    st.one_group += plan->one_group;
    apply_plan(mesh, c, *plan, rb);
  }
  rebuild_cells(mesh, rb);
  st.new_points = mesh.num_points() - np0;
  st.new_faces = mesh.num_faces() - nf0;
  st.seconds = clock.seconds();
  return st;
}

}  // namespace polydual
