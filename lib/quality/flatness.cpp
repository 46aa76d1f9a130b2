#include "quality/flatness.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

namespace polydual {

namespace {

// OpenFOAM's area vector and area-weighted centre of a polygon.
void area_and_centre(std::span<const Point3> p, Vec3& S, Point3& c) {
  const std::size_t n = p.size();
  Point3 m{};
  for (const Point3& x : p) m += x;
  m = m / double(n);
  if (n == 3) {
    S = 0.5 * cross(p[1] - p[0], p[2] - p[0]);
    c = m;
    return;
  }
  S = Vec3{};
  for (std::size_t i = 0; i < n; ++i) S += 0.5 * cross(p[(i + 1) % n] - p[i], m - p[i]);
  const double s = norm(S);
  if (!(s > 0)) {
    c = m;
    return;
  }
  const Vec3 u = S / s;
  double wsum = 0;
  Vec3 acc{};
  for (std::size_t i = 0; i < n; ++i) {
    const Point3& a = p[i];
    const Point3& b = p[(i + 1) % n];
    const double w = dot(0.5 * cross(b - a, m - a), u);
    acc += w * ((a + b + m) / 3.0);
    wsum += w;
  }
  c = wsum != 0 ? acc / wsum : m;
}

double plane_deviation(std::span<const Point3> p) {
  Point3 m{};
  for (const Point3& x : p) m += x;
  m = m / double(p.size());
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  double diameter2 = 0;  // squared: one root below (sqrt is monotone and correctly rounded)
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3 d = p[i] - m;
    const Eigen::Vector3d e(d.x, d.y, d.z);
    C += e * e.transpose();
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const Vec3 e2 = p[j] - p[i];
      diameter2 = std::max(diameter2, dot(e2, e2));
    }
  }
  const double diameter = std::sqrt(diameter2);
  if (!(diameter > 0)) return 0;
  // Closed form for 3x3 (a report statistic, not a validity decision: the
  // iterative solver cost ~7% of a whole `convert --optimize untangle`).
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(C);  // eigenvalues increasing
  const Eigen::Vector3d nv = es.eigenvectors().col(0);
  const Vec3 n{nv[0], nv[1], nv[2]};
  double worst = 0;
  for (const Point3& x : p) worst = std::max(worst, std::fabs(dot(x - m, n)));
  return worst / diameter;
}

}  // namespace

double flatness_ratio(std::span<const Point3> p) {
  if (p.size() < 3) return 1;
  Vec3 S;
  Point3 c;
  area_and_centre(p, S, c);
  double actual = 0;
  for (std::size_t i = 0; i < p.size(); ++i) actual += 0.5 * norm(cross(p[(i + 1) % p.size()] - p[i], c - p[i]));
  return actual > 0 ? std::min(1.0, norm(S) / actual) : 1.0;
}

FaceFlatness face_flatness(std::span<const Point3> p) {
  FaceFlatness f;
  if (p.size() < 3) return f;
  f.flatness = flatness_ratio(p);
  f.deviation = plane_deviation(p);
  return f;
}

Json FlatnessStats::to_json() const {
  Json j = Json::object();
  j.set("faces", faces);
  j.set("min", min_flatness);
  j.set("mean", mean_flatness);
  j.set("warped", warped);
  j.set("warped_threshold", kWarped);
  j.set("max_plane_deviation", max_deviation);
  j.set("mean_plane_deviation", mean_deviation);
  return j;
}

FlatnessStats flatness_stats(const PolyMesh& mesh) {
  // Chunks of faces measured in parallel, then summed serially in face order
  // (deterministic, and the same sums as one serial pass): one chunk's
  // values alive at a time, not one per face (16 B per face: measured as the
  // peak of a 1M-tet conversion; a chunk is 256 KB, as it runs beside the writer).
  constexpr std::size_t kChunk = std::size_t(1) << 14;
  std::vector<FaceFlatness> per(std::min(kChunk, mesh.num_faces()));
  FlatnessStats st;
  st.faces = mesh.num_faces();
  if (st.faces == 0) return st;
  double sf = 0, sd = 0;
  for (std::size_t first = 0; first < st.faces; first += kChunk) {
    const std::size_t n = std::min(kChunk, st.faces - first);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 512), [&](const auto& r) {
      std::vector<Point3> loop;
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        loop.clear();
        for (PointId p : mesh.face(FaceId(first + i))) loop.push_back(mesh.points[p.idx]);
        per[i] = face_flatness(loop);
      }
    });
    for (std::size_t i = 0; i < n; ++i) {
      const FaceFlatness& f = per[i];
      st.min_flatness = std::min(st.min_flatness, f.flatness);
      st.max_deviation = std::max(st.max_deviation, f.deviation);
      st.warped += f.flatness < FlatnessStats::kWarped;
      sf += f.flatness;
      sd += f.deviation;
    }
  }
  st.mean_flatness = sf / double(st.faces);
  st.mean_deviation = sd / double(st.faces);
  return st;
}

}  // namespace polydual
