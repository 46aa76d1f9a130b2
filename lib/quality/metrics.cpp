#include "quality/metrics.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>

#include "quality/corner.h"

namespace polydual {

const char* metric_name(Metric m) { return m == Metric::Q1 ? "q1" : "q2"; }

double corner_kappa_mod_gradient(const Vec3& e1, const Vec3& e2, const Vec3& e3, double V0,
                                 double c, Vec3& g1, Vec3& g2, Vec3& g3) {
  const Vec3 c12 = cross(e1, e2), c23 = cross(e2, e3), c31 = cross(e3, e1);
  const double n1 = norm2(e1), n2 = norm2(e2), n3 = norm2(e3);
  const double d12 = dot(e1, e2), d23 = dot(e2, e3), d31 = dot(e3, e1);
  const double A = norm2(c12) + norm2(c23) + norm2(c31);
  const double L = n1 + n2 + n3;
  const double V = dot(c12, e3);
  const double delta = adaptive_delta(V, V0, c);
  const double W = std::sqrt(V * V + delta * delta);
  const double D = regularised_volume(V, delta);
  const double S = std::sqrt(A * L);
  const double kmod = 2.0 * S / D;
  if (!(S > 0)) {  // all edges zero: no direction to prefer
    g1 = g2 = g3 = Vec3{};
    return kmod;
  }
  const double s = delta / V0;
  const double ddelta = -s * (1.0 - s);  // d delta / dV (eq. 3 scaled by V0)
  const double dD = (D + delta * ddelta) / W;  // = 1 + (V + delta delta')/W, as D = V + W
  // d|u x v|^2 / du = 2 (|v|^2 u - (u.v) v)
  const Vec3 dA1 = 2.0 * ((n2 + n3) * e1 - d12 * e2 - d31 * e3);
  const Vec3 dA2 = 2.0 * ((n1 + n3) * e2 - d12 * e1 - d23 * e3);
  const Vec3 dA3 = 2.0 * ((n1 + n2) * e3 - d31 * e1 - d23 * e2);
  const double a = 1.0 / (D * S), b = kmod / D * dD;
  g1 = a * (L * dA1 + 2.0 * A * e1) - b * c23;
  g2 = a * (L * dA2 + 2.0 * A * e2) - b * c31;
  g3 = a * (L * dA3 + 2.0 * A * e3) - b * c12;
  return kmod;
}

namespace {
// The mean kappa/3 of cell_quality from the corners' sum and count.
double quality_of(double sum, std::size_t n, bool tangled) {
  if (tangled || n == 0) return std::numeric_limits<double>::infinity();
  return sum / (3.0 * static_cast<double>(n));
}
}  // namespace

double cell_quality(const MeshStencil& s, std::uint32_t c, Metric m, std::span<const Point3> points) {
  double sum = 0;
  std::size_t n = 0;
  bool tangled = false;
  for_each_corner<double>(s, c, m, PointsPos{points.data()},
                          [&](const double* e1, const double* e2, const double* e3) {
                            const double k = corner_kappa(e1, e2, e3);
                            if (!(k > 0) || !std::isfinite(k)) tangled = true;
                            sum += k;
                            ++n;
                          });
  return quality_of(sum, n, tangled);
}

double cell_energy_and_quality(const MeshStencil& s, std::uint32_t c, Metric m, std::span<const Point3> points,
                               double V0, double c_delta, double* quality) {
  double e = 0, sum = 0;
  std::size_t n = 0;
  bool tangled = false;
  for_each_corner<double>(s, c, m, PointsPos{points.data()},
                          [&](const double* e1, const double* e2, const double* e3) {
                            double k;
                            e += corner_kappa_and_mod(e1, e2, e3, V0, c_delta, &k);
                            if (!(k > 0) || !std::isfinite(k)) tangled = true;
                            sum += k;
                            ++n;
                          });
  *quality = quality_of(sum, n, tangled);
  return e;
}

std::vector<double> cell_qualities(const MeshStencil& s, Metric m, std::span<const Point3> points) {
  std::vector<double> q(s.num_cells());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, q.size(), 512), [&](const auto& r) {
    for (std::size_t c = r.begin(); c != r.end(); ++c)
      q[c] = cell_quality(s, static_cast<std::uint32_t>(c), m, points);
  });
  return q;
}

QualityStats quality_stats(std::span<const double> q, Metric m) {
  QualityStats st;
  st.metric = m;
  st.bin_edges = {1.0, 1.1, 1.25, 1.5, 2.0, 3.0, 5.0, 10.0};
  st.histogram.assign(st.bin_edges.size(), 0);
  st.cells = q.size();
  double sum = 0;
  std::size_t n = 0;
  st.min = std::numeric_limits<double>::infinity();
  st.max = 0;
  for (double x : q) {  // serial: the sum's order, hence its bits, are fixed
    if (!std::isfinite(x)) { ++st.tangled; continue; }
    ++n;
    sum += x;
    st.min = std::min(st.min, x);
    st.max = std::max(st.max, x);
    std::size_t b = 0;
    while (b + 1 < st.bin_edges.size() && x >= st.bin_edges[b + 1]) ++b;
    ++st.histogram[b];
  }
  if (n == 0) st.min = 0;
  st.mean = n ? sum / static_cast<double>(n) : 0.0;
  return st;
}

QualityStats quality_stats(const PolyMesh& mesh, Metric m) {
  const MeshStencil s = build_stencil(mesh);
  const auto q = cell_qualities(s, m, mesh.points);
  return quality_stats(q, m);
}

Json QualityStats::to_json() const {
  Json j = Json::object();
  j.set("metric", metric_name(metric));
  j.set("cells", cells);
  j.set("tangled", tangled);
  j.set("degenerate", degenerate);
  j.set("min", min);
  j.set("mean", mean);
  j.set("max", max);
  Json e = Json::array(), h = Json::array();
  for (double x : bin_edges) e.push(x);
  for (std::size_t x : histogram) h.push(x);
  j.set("bin_edges", std::move(e));
  j.set("histogram", std::move(h));
  return j;
}

std::vector<double> cell_reference_volumes(const MeshStencil& s, Metric m,
                                           std::span<const Point3> points) {
  return cell_reference_volumes(s, m, points, nullptr);
}

namespace {
// V0 floored at 1e-3 x the mesh-wide mean (cell_reference_volumes).
std::vector<double> floored_reference_volumes(std::vector<double> v0) {
  double mean = 0;
  for (double x : v0) mean += x;
  mean = v0.empty() ? 1.0 : mean / static_cast<double>(v0.size());
  if (!(mean > 0)) mean = 1.0;
  for (double& x : v0) x = std::max(x, 1e-3 * mean);
  return v0;
}

// Two lanes of doubles (SSE2, part of x86-64): IEEE operations lane by lane,
// so each lane's bits are those of the scalar code with the same expression.
using V2 = double __attribute__((vector_size(16)));

// Sums over a Q1 cell's corners of |V| and of kappa (corner_kappa's
// expression), the corner count, and whether a corner is tangled: the two
// corners of each loop edge (at a, then at b; for_each_corner's order) in
// the two lanes, summed in that order, so the sums are for_each_corner's bit
// for bit.
struct CornerSums {
  double abs_v = 0, kappa = 0;
  std::size_t n = 0;
  bool tangled = false;
};
CornerSums q1_corner_sums(const MeshStencil& s, std::uint32_t c, std::span<const Point3> points) {
  CornerSums r;
  double R[3], F[3];
  mean_of(s.points_of(c), points.data(), R);
  for (std::uint32_t j = s.cell_loop_off[c]; j < s.cell_loop_off[c + 1]; ++j) {
    const auto loop = s.loop(j);
    const std::size_t k = loop.size();
    mean_of(loop, points.data(), F);
    const Point3* a = &points[loop[k - 1].idx];
    for (std::size_t i = 0; i < k; ++i) {
      const Point3* b = &points[loop[i].idx];
      // Lane 0: the corner at a (F-a, b-a, R-a); lane 1: at b (a-b, F-b, R-b).
      V2 e1[3], e2[3], e3[3];
      for (int d = 0; d < 3; ++d) {
        const double ad = (*a)[d], bd = (*b)[d];
        e1[d] = V2{F[d] - ad, ad - bd};
        e2[d] = V2{bd - ad, F[d] - bd};
        e3[d] = V2{R[d] - ad, R[d] - bd};
      }
      V2 A, L, V;
      corner_invariants(e1, e2, e3, A, L, V);
      const V2 AL = A * L;
      const V2 S = {std::sqrt(AL[0]), std::sqrt(AL[1])};
      const V2 kap = S / V;
      for (int lane = 0; lane < 2; ++lane) {
        r.abs_v += std::fabs(V[lane]);
        if (!(kap[lane] > 0) || !std::isfinite(kap[lane])) r.tangled = true;
        r.kappa += kap[lane];
      }
      r.n += 2;
      a = b;
    }
  }
  return r;
}
}  // namespace

std::vector<double> cell_reference_volumes(const MeshStencil& s, Metric m, std::span<const Point3> points,
                                           std::vector<double>* quality) {
  if (quality && m == Metric::Q1) {
    std::vector<double> v0(s.num_cells(), 0.0);
    quality->assign(s.num_cells(), 0.0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, v0.size(), 512), [&](const auto& r) {
      for (std::size_t c = r.begin(); c != r.end(); ++c) {
        const CornerSums cs = q1_corner_sums(s, static_cast<std::uint32_t>(c), points);
        v0[c] = cs.n ? cs.abs_v / static_cast<double>(cs.n) : 0.0;
        (*quality)[c] = quality_of(cs.kappa, cs.n, cs.tangled);
      }
    });
    return floored_reference_volumes(std::move(v0));
  }
  std::vector<double> v0(s.num_cells(), 0.0);
  if (quality) quality->assign(s.num_cells(), 0.0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, v0.size(), 512), [&](const auto& r) {
    for (std::size_t c = r.begin(); c != r.end(); ++c) {
      double sum = 0, ksum = 0;
      std::size_t n = 0;
      bool tangled = false;
      for_each_corner<double>(s, static_cast<std::uint32_t>(c), m, PointsPos{points.data()},
                              [&](const double* e1, const double* e2, const double* e3) {
                                double A, L, V;
                                corner_invariants(e1, e2, e3, A, L, V);
                                sum += std::fabs(V);
                                ++n;
                                if (!quality) return;
                                const double k = std::sqrt(A * L) / V;  // corner_kappa's expression
                                if (!(k > 0) || !std::isfinite(k)) tangled = true;
                                ksum += k;
                              });
      v0[c] = n ? sum / static_cast<double>(n) : 0.0;
      if (quality) (*quality)[c] = quality_of(ksum, n, tangled);
    }
  });
  return floored_reference_volumes(std::move(v0));
}


double cell_energy(const MeshStencil& s, std::uint32_t c, Metric m, std::span<const Point3> points,
                   double V0, double c_delta) {
  double e = 0;
  for_each_corner<double>(s, c, m, PointsPos{points.data()},
                          [&](const double* e1, const double* e2, const double* e3) {
                            e += corner_kappa_mod(e1, e2, e3, V0, c_delta);
                          });
  return e;
}

}  // namespace polydual
