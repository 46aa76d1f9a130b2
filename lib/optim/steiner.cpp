#include "optim/steiner.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "core/error.h"
#include "core/param_range.h"
#include "core/stopwatch.h"
#include "optim/tet_ops.h"
#include "predicates/predicates.h"

namespace polydual {

namespace {

using namespace tetops;

// Whether a tet with corners p and vertex sizes hs is large against the mesh
// size there: every corner farther from the centroid than ratio times the
// mean size (steiner.h). Floating point: it only chooses where to insert.
bool large_tet(const std::array<Point3, 4>& p, const std::array<double, 4>& hs, double ratio) {
  const Point3 c = 0.25 * (p[0] + p[1] + p[2] + p[3]);
  const double size = 0.25 * ratio * (hs[0] + hs[1] + hs[2] + hs[3]);
  return std::all_of(p.begin(), p.end(), [&](const Point3& q) { return norm(q - c) > size; });
}

// A cavity grown from one tet: its tets (the first is the seed) and a stamp
// per slot telling membership in O(1).
struct Cavity {
  std::vector<std::uint32_t> tets;
  std::vector<std::uint32_t> stamp;
  std::uint32_t id = 0;
  bool has(std::uint32_t t) const { return t < stamp.size() && stamp[t] == id; }
  void reset(std::size_t slots) {
    ++id;
    tets.clear();
    if (stamp.size() < slots) stamp.resize(slots, 0);
  }
  void add(std::uint32_t t) {
    stamp[t] = id;
    tets.push_back(t);
  }
};

// Cavities stay small on the meshes this serves (Delaunay-like tets around a
// centroid); the bound only caps the work of a pathological one.
constexpr std::size_t kMaxCavity = 256;
// As the flips (optim/tet_flip.cpp): a new tet may be worse than the ones it
// replaces, but not past this or past the worst of them (floating point).
constexpr double kQualityCap = 1e3;

enum class Outcome { Inserted, Visibility, Topology, Quality };

class Inserter {
 public:
  Inserter(FlipMesh& w, std::vector<double>& h) : w_(w), h_(h) {}

  bool large(std::uint32_t t, double ratio) const {
    const Tet& a = w_.tv[t];
    return large_tet({w_.p(a[0]), w_.p(a[1]), w_.p(a[2]), w_.p(a[3])}, {h_[a[0]], h_[a[1]], h_[a[2]], h_[a[3]]},
                     ratio);
  }

  Outcome insert_centroid(std::uint32_t t0) {
    const Point3 c = centroid(t0);
    grow(t0, c);
    if (!shrink(t0, c)) return Outcome::Visibility;
    if (!keeps_topology(t0)) return Outcome::Topology;
    const std::uint32_t v = std::uint32_t(w_.pts.size());
    std::vector<Tet> fresh;
    double worst = kQualityCap;
    for (std::uint32_t t : cav_.tets) worst = std::max(worst, w_.quality(w_.tv[t]));
    w_.pts.push_back(c);
    for (std::uint32_t t : cav_.tets)
      for (int i = 0; i < 4; ++i)
        if (on_cavity_boundary(t, i)) {
          Tet n = w_.tv[t];
          n[i] = v;
          fresh.push_back(n);
        }
    for (const Tet& n : fresh)
      if (!(w_.quality(n) <= worst)) {
        w_.pts.pop_back();
        return Outcome::Quality;
      }
    double size = 0;
    for (std::uint32_t u : w_.tv[t0]) size += 0.25 * h_[u];
    h_.push_back(size);
    w_.new_vertex_region.push_back(w_.region[t0]);
    replace(w_, cav_.tets, fresh);
    w_.queue.clear();  // the flips' work list: not used here
    return Outcome::Inserted;
  }

 private:
  Point3 centroid(std::uint32_t t) const {
    const Tet& a = w_.tv[t];
    return 0.25 * (w_.p(a[0]) + w_.p(a[1]) + w_.p(a[2]) + w_.p(a[3]));
  }
  std::uint32_t neighbour(std::uint32_t t, int i) const {
    const std::uint32_t n = w_.nb[t][i];
    return n == kNone ? kNone : n >> 2;
  }
  bool on_cavity_boundary(std::uint32_t t, int i) const {
    const std::uint32_t u = neighbour(t, i);
    return u == kNone || !cav_.has(u);
  }
  // Tets whose circumsphere holds c strictly (EXACT), reached from t0
  // through faces on no model face.
  void grow(std::uint32_t t0, const Point3& c) {
    cav_.reset(w_.tv.size());
    cav_.add(t0);
    for (std::size_t k = 0; k < cav_.tets.size() && cav_.tets.size() < kMaxCavity; ++k)
      for (int i = 0; i < 4; ++i) {
        const std::uint32_t u = neighbour(cav_.tets[k], i);
        if (u == kNone || w_.ftag[cav_.tets[k]][i] != kNoFace || cav_.has(u)) continue;
        const Tet& a = w_.tv[u];
        if (insphere(w_.p(a[0]), w_.p(a[1]), w_.p(a[2]), w_.p(a[3]), c) == Sign::Positive) cav_.add(u);
      }
  }
  // Drops the tets with a face that c does not see (the new tet would not be
  // positive, EXACT) and those no longer reached from t0, until c sees every
  // face; false if a face of t0 itself is not seen.
  bool shrink(std::uint32_t t0, const Point3& c) {
    for (;;) {
      std::vector<std::uint32_t> keep;
      bool dropped = false;
      for (std::uint32_t t : cav_.tets) {
        bool sees = true;
        for (int i = 0; i < 4 && sees; ++i) {
          if (!on_cavity_boundary(t, i)) continue;
          std::array<Point3, 4> q{w_.p(w_.tv[t][0]), w_.p(w_.tv[t][1]), w_.p(w_.tv[t][2]), w_.p(w_.tv[t][3])};
          q[i] = c;
          sees = orient3d(q[0], q[1], q[2], q[3]) == Sign::Positive;
        }
        if (!sees && t == t0) return false;
        if (sees) keep.push_back(t);
        dropped |= !sees;
      }
      if (!dropped) return true;
      reconnect(t0, keep);
    }
  }
  // The cavity becomes the tets of `keep` reached from t0 through faces on no
  // model face.
  void reconnect(std::uint32_t t0, const std::vector<std::uint32_t>& keep) {
    cav_.reset(w_.tv.size());
    for (std::uint32_t t : keep) cav_.stamp[t] = cav_.id;  // candidates
    const std::uint32_t candidate = cav_.id;
    cav_.reset(w_.tv.size());
    std::vector<std::uint32_t> stack{t0};
    std::vector<std::uint32_t>& st = cav_.stamp;
    st[t0] = cav_.id;
    cav_.tets.push_back(t0);
    while (!stack.empty()) {
      const std::uint32_t t = stack.back();
      stack.pop_back();
      for (int i = 0; i < 4; ++i) {
        const std::uint32_t u = neighbour(t, i);
        if (u == kNone || w_.ftag[t][i] != kNoFace || st[u] != candidate) continue;
        st[u] = cav_.id;
        cav_.tets.push_back(u);
        stack.push_back(u);
      }
    }
  }
  // Nothing but tets goes: no vertex inside the cavity, no constrained edge
  // and no model-face triangle between two of its tets, one region.
  bool keeps_topology(std::uint32_t t0) const {
    std::vector<std::uint32_t> inner_vertices, outer_vertices;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> outer_edges;
    for (std::uint32_t t : cav_.tets) {
      if (w_.region[t] != w_.region[t0]) return false;
      for (int i = 0; i < 4; ++i) {
        if (!on_cavity_boundary(t, i)) {
          if (w_.ftag[t][i] != kNoFace) return false;
          continue;
        }
        const auto k = face_key(w_.tv[t], i);
        outer_vertices.insert(outer_vertices.end(), k.begin(), k.end());
        outer_edges.insert(outer_edges.end(), {{k[0], k[1]}, {k[0], k[2]}, {k[1], k[2]}});
      }
      inner_vertices.insert(inner_vertices.end(), w_.tv[t].begin(), w_.tv[t].end());
    }
    auto unique_sorted = [](auto& v) {
      std::sort(v.begin(), v.end());
      v.erase(std::unique(v.begin(), v.end()), v.end());
    };
    unique_sorted(inner_vertices), unique_sorted(outer_vertices), unique_sorted(outer_edges);
    if (inner_vertices != outer_vertices) return false;
    for (std::uint32_t t : cav_.tets)
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b) {
          const auto e = std::minmax(w_.tv[t][a], w_.tv[t][b]);
          if (!std::binary_search(outer_edges.begin(), outer_edges.end(), std::make_pair(e.first, e.second)) &&
              w_.cedges.find(e.first, e.second))
            return false;
        }
    return true;
  }

  FlipMesh& w_;
  std::vector<double>& h_;
  Cavity cav_;
};

// Per vertex, the mesh size h (steiner.h).
std::vector<double> vertex_sizes(const ClassifiedTetMesh& m) {
  std::vector<double> model_sum(m.num_vertices(), 0), all_sum(m.num_vertices(), 0);
  std::vector<std::uint32_t> model_n(m.num_vertices(), 0), all_n(m.num_vertices(), 0);
  for (std::size_t e = 0; e < m.num_edges(); ++e) {
    const auto [a, b] = m.edge(EdgeId(e));
    const double len = norm(m.point(a) - m.point(b));
    const bool model = m.edge_class(EdgeId(e)).dim < 3;
    for (VertexId v : {a, b}) {
      all_sum[v.idx] += len, ++all_n[v.idx];
      if (model) model_sum[v.idx] += len, ++model_n[v.idx];
    }
  }
  std::vector<double> h(m.num_vertices(), 0);
  for (std::size_t v = 0; v < h.size(); ++v) {
    const bool interior = m.vertex_class(VertexId(v)).dim == 3 || model_n[v] == 0;
    h[v] = interior ? all_sum[v] / std::max<std::uint32_t>(all_n[v], 1) : model_sum[v] / model_n[v];
  }
  return h;
}

// Whether a tet of m is large (large_tet).
bool any_large(const ClassifiedTetMesh& m, const std::vector<double>& h, double ratio) {
  for (std::size_t t = 0; t < m.num_tets(); ++t) {
    const auto& v = m.tet(TetId(t));
    if (large_tet({m.point(v[0]), m.point(v[1]), m.point(v[2]), m.point(v[3])},
                  {h[v[0].idx], h[v[1].idx], h[v[2].idx], h[v[3].idx]}, ratio))
      return true;
  }
  return false;
}

void count(Outcome o, SteinerReport& rep) {
  switch (o) {
    case Outcome::Inserted: ++rep.inserted; break;
    case Outcome::Visibility: ++rep.skipped_visibility; break;
    case Outcome::Topology: ++rep.skipped_topology; break;
    case Outcome::Quality: ++rep.skipped_quality; break;
  }
}

}  // namespace

void SteinerParams::validate() const {
  check_param("SteinerParams::ratio", "ratio", {kMinRatio, kMaxRatio}, ratio);
  check_param("SteinerParams::ratio_without_optimiser", "ratio", {kMinRatio, kMaxRatio}, ratio_without_optimiser);
  check_param("SteinerParams::max_passes", "passes", {0, double(kMaxPasses)}, max_passes);
  check_param("SteinerParams::max_points_per_vertex", "points per vertex", {0, 100}, max_points_per_vertex);
}

Json SteinerParams::to_json() const {
  Json j = Json::object();
  j.set("enabled", enabled);
  j.set("ratio", ratio);
  j.set("ratio_without_optimiser", ratio_without_optimiser);
  j.set("max_passes", max_passes);
  j.set("max_points_per_vertex", max_points_per_vertex);
  return j;
}

Json SteinerReport::to_json() const {
  Json j = Json::object();
  j.set("interior_vertices_before", interior_vertices_before);
  j.set("candidates", candidates);
  j.set("inserted", inserted);
  Json skipped = Json::object();
  skipped.set("visibility", skipped_visibility);
  skipped.set("topology", skipped_topology);
  skipped.set("quality", skipped_quality);
  j.set("skipped", skipped);
  j.set("passes", passes);
  j.set("hit_limit", hit_limit);
  if (!failed.empty()) j.set("failed", failed);
  j.set("seconds", seconds);
  return j;
}

ClassifiedTetMesh insert_interior_points(const ClassifiedTetMesh& mesh, const SteinerParams& params,
                                         SteinerReport* report) {
  params.validate();
  const Stopwatch clock;
  SteinerReport rep;
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) rep.interior_vertices_before += mesh.vertex_class(VertexId(v)).dim == 3;
  std::vector<double> h = vertex_sizes(mesh);
  if (!any_large(mesh, h, params.ratio)) {  // the common case: no work, no copy of the mesh
    rep.seconds = clock.seconds();
    if (report) *report = rep;
    return mesh;
  }
  FlipMesh w(mesh);
  Inserter ins(w, h);
  const auto limit = std::size_t(params.max_points_per_vertex * double(mesh.num_vertices()));
  for (int pass = 0; pass < params.max_passes && !rep.hit_limit; ++pass) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> candidates;  // (slot, version)
    for (std::uint32_t t = 0; t < w.tv.size(); ++t)
      if (w.alive[t] && ins.large(t, params.ratio)) candidates.emplace_back(t, w.version[t]);
    if (candidates.empty()) break;
    ++rep.passes;
    rep.candidates += candidates.size();
    const std::size_t before = rep.inserted;
    for (const auto& [t, version] : candidates) {
      if (!w.alive[t] || w.version[t] != version) continue;  // changed by an insertion of this pass
      if (rep.inserted >= limit) {
        rep.hit_limit = true;
        break;
      }
      count(ins.insert_centroid(t), rep);
    }
    if (rep.inserted == before) break;
  }
  ClassifiedTetMesh out = mesh;
  if (rep.inserted > 0) try {
      out = rebuild(mesh, w);
    } catch (const InputError& e) {
      // A guard, as for the flips: the points are an improvement, never a
      // condition of correctness.
      rep.failed = std::string(e.what());
      rep.inserted = 0;
    }
  rep.seconds = clock.seconds();
  if (report) *report = rep;
  return out;
}

}  // namespace polydual
