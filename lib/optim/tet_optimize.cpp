#include "optim/tet_optimize.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/param_range.h"
#include "core/stopwatch.h"
#include "optim/boundary.h"
#include "predicates/predicates.h"
#include "quality/corner.h"

namespace polydual {

namespace {

// Corner i of a positive tet: local vertex kCorner[i][0] and the other three in
// an even permutation of (0,1,2,3), so its edge vectors are right-handed.
constexpr int kCorner[4][4] = {{0, 1, 2, 3}, {1, 0, 3, 2}, {2, 3, 0, 1}, {3, 2, 1, 0}};

// Floor of the per-tet V0 relative to the mesh-wide mean (as the dual's
// cell_reference_volumes): a near-flat tet still has a positive scale.
constexpr double kV0Floor = 1e-3;

// What constrains one vertex: its degrees of freedom, its original entity
// pieces around it (triangles of its model face or segments of its model
// edge, original coordinates) and a tangent basis of them.
struct VertexFrame {
  std::uint8_t dof = 0;
  std::vector<std::array<Point3, 3>> pieces;  // segments use [0], [1]
  std::array<Vec3, 3> basis{};
};

Vec3 unit(Vec3 v) { return v / norm(v); }

// Any unit vector orthogonal to unit n.
Vec3 orthogonal(Vec3 n) {
  const Vec3 a = std::fabs(n.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  return unit(cross(n, a));
}

// Model-face triangles of `tag` around v (each once, by increasing TriId).
std::vector<TriId> umbrella(const ClassifiedTetMesh& m, VertexId v, std::int32_t tag) {
  std::vector<TriId> tris;
  for (TetId t : m.vertex_tets(v)) {
    const int li = m.local_index(t, v);
    for (int f = 0; f < 4; ++f) {
      if (f == li) continue;
      const TriId tri = m.tet_triangle(t, f);
      if (m.triangle_class(tri) == ModelRef{2, tag}) tris.push_back(tri);
    }
  }
  std::sort(tris.begin(), tris.end(), [](TriId a, TriId b) { return a.idx < b.idx; });
  tris.erase(std::unique(tris.begin(), tris.end()), tris.end());
  return tris;
}

// The other ends of the model-edge segments of `tag` at v, by increasing id.
std::vector<VertexId> edge_neighbours(const ClassifiedTetMesh& m, VertexId v, std::int32_t tag) {
  std::vector<VertexId> ends;
  for (TetId t : m.vertex_tets(v))
    for (int k = 0; k < 6; ++k) {
      if (m.edge_class(m.tet_edge(t, k)) != ModelRef{1, tag}) continue;
      const auto [a, b] = m.edge(m.tet_edge(t, k));
      if (a == v) ends.push_back(b);
      else if (b == v) ends.push_back(a);
    }
  std::sort(ends.begin(), ends.end());
  ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
  return ends;
}

VertexFrame face_frame(const ClassifiedTetMesh& m, VertexId v, std::int32_t tag) {
  VertexFrame fr;
  Vec3 n{};
  for (TriId tri : umbrella(m, v, tag)) {
    const auto tv = m.triangle(tri);
    const std::array<Point3, 3> p = {m.point(tv[0]), m.point(tv[1]), m.point(tv[2])};
    Vec3 ni = cross(p[1] - p[0], p[2] - p[0]);
    if (dot(ni, n) < 0) ni = -1.0 * ni;  // triangles of an interface are not oriented alike
    n += ni;
    fr.pieces.push_back(p);
  }
  if (fr.pieces.empty() || !(norm(n) > 0)) return VertexFrame{};
  n = unit(n);
  fr.dof = 2;
  fr.basis[0] = orthogonal(n);
  fr.basis[1] = cross(n, fr.basis[0]);
  return fr;
}

VertexFrame edge_frame(const ClassifiedTetMesh& m, VertexId v, std::int32_t tag) {
  const std::vector<VertexId> ends = edge_neighbours(m, v, tag);
  if (ends.size() != 2) return VertexFrame{};  // an end or a branch of the curve: fixed
  VertexFrame fr;
  for (VertexId e : ends) fr.pieces.push_back({m.point(v), m.point(e), m.point(e)});
  const Vec3 d = m.point(ends[1]) - m.point(ends[0]);
  if (!(norm(d) > 0)) return VertexFrame{};
  fr.dof = 1;
  fr.basis[0] = unit(d);
  return fr;
}

// Whether the model-face triangles around v are all in one plane, for every
// model face through v (EXACT: orient3d of each of their vertices against
// the first triangle), and, on a model edge, its two segments at v on one
// line (EXACT: orient2d in the three coordinate planes).
bool flat_at(const ClassifiedTetMesh& m, VertexId v) {
  std::vector<std::int32_t> tags;
  for (TetId t : m.vertex_tets(v)) {
    const int li = m.local_index(t, v);
    for (int f = 0; f < 4; ++f)
      if (const ModelRef c = m.triangle_class(m.tet_triangle(t, f)); f != li && c.dim == 2) tags.push_back(c.tag);
  }
  std::sort(tags.begin(), tags.end());
  tags.erase(std::unique(tags.begin(), tags.end()), tags.end());
  for (std::int32_t tag : tags) {
    const std::vector<TriId> tris = umbrella(m, v, tag);
    const auto t0 = m.triangle(tris[0]);
    for (TriId tri : tris)
      for (VertexId w : m.triangle(tri))
        if (orient3d(m.point(t0[0]), m.point(t0[1]), m.point(t0[2]), m.point(w)) != Sign::Zero) return false;
  }
  const ModelRef r = m.vertex_class(v);
  if (r.dim != 1) return true;
  const std::vector<VertexId> ends = edge_neighbours(m, v, r.tag);
  if (ends.size() != 2) return true;
  const Point3 a = m.point(ends[0]), b = m.point(v), c = m.point(ends[1]);
  return orient2d(a.x, a.y, b.x, b.y, c.x, c.y) == Sign::Zero && orient2d(a.y, a.z, b.y, b.z, c.y, c.z) == Sign::Zero &&
         orient2d(a.z, a.x, b.z, b.x, c.z, c.x) == Sign::Zero;
}

VertexFrame make_frame(const ClassifiedTetMesh& m, VertexId v, bool move_curved) {
  const ModelRef r = m.vertex_class(v);
  if (!move_curved && r.dim != 3 && !flat_at(m, v)) return VertexFrame{};
  if (r.dim == 1) return edge_frame(m, v, r.tag);
  if (r.dim == 2) return face_frame(m, v, r.tag);
  if (r.dim == 3) {
    VertexFrame fr;
    fr.dof = 3;
    fr.basis = {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
    return fr;
  }
  return VertexFrame{};  // model vertex or unclassified: fixed
}

// Nearest point of the vertex's original pieces to x (first nearest on ties).
Point3 project(const VertexFrame& fr, const Point3& x) {
  if (fr.dof == 3) return x;
  Point3 best = x;
  double d2 = std::numeric_limits<double>::infinity();
  for (const auto& p : fr.pieces) {
    const Point3 q = fr.dof == 1 ? closest_point_on_segment(x, p[0], p[1]) : closest_point_on_triangle(x, p[0], p[1], p[2]);
    const double e = norm2(q - x);
    if (e < d2) { d2 = e; best = q; }
  }
  return best;
}

// Greedy colouring of the vertex graph (vertices sharing a tet), in vertex
// order: deterministic. Returns the colour of each vertex.
std::vector<std::uint32_t> colour_vertices(const ClassifiedTetMesh& m, const std::vector<VertexFrame>& frames,
                                           std::uint32_t* num_colours) {
  constexpr std::uint32_t kNone = UINT32_MAX;
  std::vector<std::uint32_t> colour(m.num_vertices(), kNone);
  std::vector<std::uint32_t> seen;  // seen[c] == v + 1: colour c is taken around v
  std::uint32_t n = 0;
  for (std::uint32_t v = 0; v < m.num_vertices(); ++v) {
    if (frames[v].dof == 0) continue;
    for (TetId t : m.vertex_tets(VertexId(v)))
      for (VertexId w : m.tet(t))
        if (colour[w.idx] != kNone) seen[colour[w.idx]] = v + 1;
    std::uint32_t c = 0;
    while (c < seen.size() && seen[c] == v + 1) ++c;
    if (c == seen.size()) seen.push_back(0);
    colour[v] = c;
    n = std::max(n, c + 1);
  }
  *num_colours = n;
  return colour;
}

struct State {
  const ClassifiedTetMesh& mesh;
  const TetOptParams& params;
  std::vector<Point3> pts;
  std::vector<double> V0;  // per tet, fixed for the run
  std::vector<VertexFrame> frames;
};

// Sum of kappa_mod over the corners of tet t with vertex v (local li) at x;
// with g and H, adds the gradient and Hessian with respect to x.
double tet_energy(const State& s, TetId t, int li, const Point3& x, double g[3], double H[9]) {
  const auto& tv = s.mesh.tet(t);
  Point3 P[4];
  for (int i = 0; i < 4; ++i) P[i] = i == li ? x : s.pts[tv[i].idx];
  double f = 0;
  for (const auto& c : kCorner) {
    double e[3][3];
    double a[3];
    for (int j = 0; j < 3; ++j) {
      const Vec3 d = P[c[j + 1]] - P[c[0]];
      e[j][0] = d.x, e[j][1] = d.y, e[j][2] = d.z;
      a[j] = c[0] == li ? -1.0 : (c[j + 1] == li ? 1.0 : 0.0);
    }
    f += g ? corner_kappa_mod_add_point_derivatives(e[0], e[1], e[2], a[0], a[1], a[2], s.V0[t.idx], s.params.c, g, H)
           : corner_kappa_mod<double>(e[0], e[1], e[2], s.V0[t.idx], s.params.c);
  }
  return f;
}

double vertex_energy(const State& s, VertexId v, const Point3& x, double g[3], double H[9]) {
  double f = 0;
  for (TetId t : s.mesh.vertex_tets(v)) f += tet_energy(s, t, s.mesh.local_index(t, v), x, g, H);
  return f;
}

// Every tet around v positive by the exact orient3d with v at x.
bool star_positive(const State& s, VertexId v, const Point3& x) {
  for (TetId t : s.mesh.vertex_tets(v)) {
    const auto& tv = s.mesh.tet(t);
    Point3 P[4];
    for (int i = 0; i < 4; ++i) P[i] = tv[i] == v ? x : s.pts[tv[i].idx];
    if (orient3d(P[0], P[1], P[2], P[3]) != Sign::Positive) return false;
  }
  return true;
}

// Newton direction in the vertex's tangent space (Levenberg-damped until the
// reduced Hessian is positive definite), capped at the local length.
Vec3 newton_direction(const VertexFrame& fr, const double g[3], const double H[9], double length) {
  const int k = fr.dof;
  Eigen::Matrix3d Hm = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(H);
  Eigen::Vector3d gv(g[0], g[1], g[2]);
  Eigen::MatrixXd B(3, k);
  for (int j = 0; j < k; ++j) B.col(j) = Eigen::Vector3d(fr.basis[j].x, fr.basis[j].y, fr.basis[j].z);
  const Eigen::MatrixXd Ht = B.transpose() * Hm * B;
  const Eigen::VectorXd gt = B.transpose() * gv;
  if (!gt.allFinite() || !Ht.allFinite() || gt.norm() == 0) return Vec3{};
  double lambda = 0;
  const double scale = std::max(Ht.diagonal().cwiseAbs().maxCoeff(), 1e-300);
  Eigen::VectorXd d;
  for (int attempt = 0; attempt < 30; ++attempt) {
    Eigen::LLT<Eigen::MatrixXd> llt(Ht + lambda * Eigen::MatrixXd::Identity(k, k));
    if (llt.info() == Eigen::Success) {
      d = -llt.solve(gt);
      break;
    }
    lambda = lambda == 0 ? 1e-6 * scale : 10 * lambda;
  }
  if (d.size() == 0 || !d.allFinite()) d = -gt * (length / gt.norm());
  Eigen::Vector3d step = B * d;
  if (step.norm() > length) step *= length / step.norm();
  return Vec3{step[0], step[1], step[2]};
}

struct VisitResult {
  bool moved = false;
  std::uint32_t rejected_invalid = 0;
};

// One Newton step at v with step halving; writes s.pts[v] on acceptance.
VisitResult visit(State& s, VertexId v) {
  const VertexFrame& fr = s.frames[v.idx];
  const Point3 x0 = s.pts[v.idx];
  double g[3] = {0, 0, 0}, H[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  const double f0 = vertex_energy(s, v, x0, g, H);
  double length = std::numeric_limits<double>::infinity();
  for (TetId t : s.mesh.vertex_tets(v)) length = std::min(length, std::cbrt(s.V0[t.idx]));
  const Vec3 d = newton_direction(fr, g, H, length);
  VisitResult r;
  if (d == Vec3{}) return r;
  double alpha = 1;
  for (int h = 0; h <= s.params.max_halvings; ++h, alpha *= 0.5) {
    const Point3 x = project(fr, x0 + alpha * d);
    if (x == x0) break;
    if (!star_positive(s, v, x)) {
      ++r.rejected_invalid;
      continue;
    }
    if (vertex_energy(s, v, x, nullptr, nullptr) < f0) {
      s.pts[v.idx] = x;
      r.moved = true;
      break;
    }
  }
  return r;
}

double total_energy(const State& s) {
  std::vector<double> e(s.mesh.num_tets());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, e.size(), 1024), [&](const auto& r) {
    for (std::size_t t = r.begin(); t != r.end(); ++t) {
      const VertexId v0 = s.mesh.tet(TetId(t))[0];
      e[t] = tet_energy(s, TetId(t), 0, s.pts[v0.idx], nullptr, nullptr);
    }
  });
  double sum = 0;  // serial: deterministic
  for (double x : e) sum += x;
  return sum;
}

std::vector<double> reference_volumes(const ClassifiedTetMesh& m) {
  std::vector<double> V0(m.num_tets());
  double mean = 0;
  for (std::size_t t = 0; t < V0.size(); ++t) {
    V0[t] = std::fabs(6.0 * m.tet_volume(TetId(t)));
    mean += V0[t];
  }
  mean /= double(std::max<std::size_t>(V0.size(), 1));
  for (double& v : V0) v = std::max(v, kV0Floor * mean);
  return V0;
}

// The sweeps: each visits the colours in order, a colour's vertices in parallel.
void run_sweeps(State& s, const std::vector<std::vector<VertexId>>& by_colour, TetOptReport& rep) {
  double f_prev = total_energy(s);
  rep.objective.push_back(f_prev);
  for (int sweep = 1; sweep <= s.params.max_sweeps; ++sweep) {
    std::uint64_t moves = 0;
    for (const auto& verts : by_colour) {
      std::vector<VisitResult> res(verts.size());
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, verts.size(), 64), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) res[i] = visit(s, verts[i]);
      });
      for (const VisitResult& x : res) {
        moves += x.moved;
        rep.rejected_invalid += x.rejected_invalid;
      }
      rep.visits += verts.size();
    }
    rep.moves += moves;
    rep.sweeps = sweep;
    const double f = total_energy(s);
    rep.objective.push_back(f);
    if (moves == 0 || std::fabs(f_prev - f) < s.params.tol * std::fabs(f_prev)) break;
    f_prev = f;
  }
}

}  // namespace

void TetOptParams::validate() const {
  check_param("tet optimisation max_sweeps", "sweeps", {0, double(kMaxSweeps)}, max_sweeps);
  check_param("tet optimisation tol", "relative", {0, kMaxTol}, tol);
  check_param("tet optimisation max_halvings", "halvings", {0, double(kMaxHalvings)}, max_halvings);
  check_param("tet optimisation c", "eq. 3", {kMinDeltaC, kMaxDeltaC}, c);
  flips.validate();
  steiner.validate();
}

Json TetOptParams::to_json() const {
  Json j = Json::object();
  j.set("enabled", enabled);
  j.set("move_curved", move_curved);
  j.set("max_sweeps", max_sweeps);
  j.set("tol", tol);
  j.set("max_halvings", max_halvings);
  j.set("c", c);
  j.set("flips", flips.to_json());
  j.set("interior_points", steiner.to_json());
  return j;
}

double tet_quality(const Point3& p0, const Point3& p1, const Point3& p2, const Point3& p3) {
  const Point3 P[4] = {p0, p1, p2, p3};
  double q = 0;
  for (const auto& c : kCorner) {
    double e[3][3];
    for (int j = 0; j < 3; ++j) {
      const Vec3 d = P[c[j + 1]] - P[c[0]];
      e[j][0] = d.x, e[j][1] = d.y, e[j][2] = d.z;
    }
    const double k = corner_kappa<double>(e[0], e[1], e[2]);
    if (!(k > 0)) return std::numeric_limits<double>::infinity();
    q += k / 3.0;
  }
  return q / 4.0;
}

Json TetQualityStats::to_json() const {
  Json j = Json::object();
  j.set("tets", tets);
  j.set("min", min);
  j.set("mean", mean);
  j.set("max", max);
  return j;
}

TetQualityStats tet_quality_stats(const ClassifiedTetMesh& m, std::span<const Point3> pts) {
  TetQualityStats st;
  st.tets = m.num_tets();
  if (st.tets == 0) return st;
  st.min = std::numeric_limits<double>::infinity();
  double sum = 0;
  for (std::size_t t = 0; t < m.num_tets(); ++t) {
    const auto& v = m.tet(TetId(t));
    const double q = tet_quality(pts[v[0].idx], pts[v[1].idx], pts[v[2].idx], pts[v[3].idx]);
    st.min = std::min(st.min, q);
    st.max = std::max(st.max, q);
    sum += q;
  }
  st.mean = sum / double(st.tets);
  return st;
}

Json TetOptReport::to_json() const {
  Json j = Json::object();
  j.set("before", before.to_json());
  j.set("after_moves", after_moves.to_json());
  j.set("after", after.to_json());
  j.set("sweeps", sweeps);
  j.set("colours", colours);
  j.set("movable", movable);
  j.set("visits", visits);
  j.set("moves", moves);
  j.set("rejected_invalid", rejected_invalid);
  Json obj = Json::array();
  for (double f : objective) obj.push(f);
  j.set("objective", obj);
  j.set("rounds", rounds);
  j.set("seconds", seconds);
  if (flipped) j.set("flips", flips.to_json());
  j.set("interior_points", steiner.to_json());
  return j;
}

std::vector<Point3> optimized_tet_points(const ClassifiedTetMesh& mesh, const TetOptParams& params,
                                         TetOptReport* report) {
  params.validate();
  const Stopwatch clock;
  State s{mesh, params, mesh.points(), reference_volumes(mesh), {}};
  s.frames.resize(mesh.num_vertices());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.num_vertices(), 256), [&](const auto& r) {
    for (std::size_t v = r.begin(); v != r.end(); ++v) s.frames[v] = make_frame(mesh, VertexId(v), params.move_curved);
  });
  TetOptReport rep;
  rep.before = tet_quality_stats(mesh, s.pts);
  const std::vector<std::uint32_t> colour = colour_vertices(mesh, s.frames, &rep.colours);
  std::vector<std::vector<VertexId>> by_colour(rep.colours);
  for (std::uint32_t v = 0; v < mesh.num_vertices(); ++v)
    if (s.frames[v].dof > 0) by_colour[colour[v]].push_back(VertexId(v));
  for (const auto& c : by_colour) rep.movable += c.size();
  run_sweeps(s, by_colour, rep);
  rep.after = rep.after_moves = tet_quality_stats(mesh, s.pts);
  rep.seconds = clock.seconds();
  if (report) *report = std::move(rep);
  return std::move(s.pts);
}

ClassifiedTetMesh with_points(const ClassifiedTetMesh& mesh, std::vector<Point3> points) {
  if (points.size() != mesh.num_vertices())
    throw UsageError("with_points: " + std::to_string(points.size()) + " points for a mesh of " +
                     std::to_string(mesh.num_vertices()) + " vertices");
  for (std::size_t t = 0; t < mesh.num_tets(); ++t) {
    const auto& v = mesh.tet(TetId(t));
    if (orient3d(points[v[0].idx], points[v[1].idx], points[v[2].idx], points[v[3].idx]) != Sign::Positive)
      throw InputError(mesh.source(), "tet " + std::to_string(mesh.input_tet(TetId(t))),
                       "not positively oriented after moving its vertices");
  }
  return mesh.with_points(std::move(points));
}

namespace {

// Adds one round's move statistics to the stage's report.
void add_round(TetOptReport& rep, const TetOptReport& r) {
  rep.sweeps += r.sweeps;
  rep.colours = std::max(rep.colours, r.colours);
  rep.movable = r.movable;
  rep.visits += r.visits, rep.moves += r.moves, rep.rejected_invalid += r.rejected_invalid;
  rep.objective.insert(rep.objective.end(), r.objective.begin(), r.objective.end());
  rep.after_moves = r.after;
  ++rep.rounds;
}

}  // namespace

ClassifiedTetMesh optimize_tets(const ClassifiedTetMesh& input, const TetOptParams& params, TetOptReport* report) {
  params.validate();
  const Stopwatch clock;
  TetOptReport rep;
  rep.before = tet_quality_stats(input, input.points());
  ClassifiedTetMesh mesh =
      params.steiner.enabled ? insert_interior_points(input, params.steiner, &rep.steiner) : input;
  const int rounds = params.flips.enabled ? params.flips.rounds : 1;
  for (int round = 0; round < rounds; ++round) {
    TetOptReport r;
    std::vector<Point3> pts = optimized_tet_points(mesh, params, &r);
    add_round(rep, r);
    mesh = with_points(mesh, std::move(pts));
    if (!params.flips.enabled) continue;
    TetFlipReport f;
    mesh = delaunay_flips(mesh, params.flips, &f);
    if (round == 0) rep.flips = f;
    else rep.flips.accumulate(f);
    rep.flipped = true;
  }
  rep.after = tet_quality_stats(mesh, mesh.points());
  rep.seconds = clock.seconds();
  if (report) *report = std::move(rep);
  return mesh;
}

}  // namespace polydual
