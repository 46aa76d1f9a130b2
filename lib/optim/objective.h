// The optimisation objective (paper 3.3, design §7): the sum of kappa_mod over all
// corners of the chosen metric (Q1 or Q2), with delta(V) of eq. 3 scaled by a
// per-cell V0 fixed for the run.
#pragma once
#include <span>

#include "quality/corner.h"
#include "quality/stencil.h"

namespace polydual {

// The part of the global objective that depends on point p: every corner of
// every cell containing p. All of them depend on p, because the region centre R
// of such a cell moves with p (and so do the face centres F of p's faces).
// Templated so the same text serves doubles (finite differences) and ceres::Jet
// (exact gradient): x is p's trial position, all other points are read from pts.
struct LocalObjective {
  const MeshStencil& s;
  const Point3* pts;
  const double* V0;  // per cell
  Metric metric;
  double c;          // eq. 3
  PointId p;

  template <class T>
  T operator()(const T x[3]) const {
    const auto pos = [&](PointId q, T out[3]) {
      if (q == p) {
        out[0] = x[0]; out[1] = x[1]; out[2] = x[2];
      } else {
        const Point3& y = pts[q.idx];
        out[0] = T(y.x); out[1] = T(y.y); out[2] = T(y.z);
      }
    };
    T sum(0.0);
    for (std::uint32_t cell : s.cells_of(p)) {
      const double v0 = V0[cell];
      for_each_corner<T>(s, cell, metric, pos, [&](const T* e1, const T* e2, const T* e3) {
        sum += corner_kappa_mod(e1, e2, e3, v0, c);
      });
    }
    return sum;
  }
};

// The local objective of point p (LocalObjective at p's current position in
// pts) with its analytic gradient g (3) and Hessian H (3x3 row-major) with
// respect to p's coordinates, in one pass over p's corners
// (corner_kappa_mod_add_point_derivatives). The returned value is bitwise equal
// to LocalObjective<double> at pts[p] (same corners, same order, same
// arithmetic). The default derivatives of the local scheme.
double local_objective_derivatives(const MeshStencil& s, const Point3* pts, const double* V0, Metric m,
                                   double c, PointId p, double g[3], double H[9]);

// Energy of cell c (sum of kappa_mod over its corners) and, if grad != nullptr,
// its gradient with respect to the cell's points, written to grad[i] for the
// i-th point of s.points_of(c) (reverse-mode chain rule through F and R, from
// corner_kappa_mod_gradient). Used by the global scheme. If grad_R != nullptr,
// *grad_R = the sum over the cell's corners of d kappa_mod / d R; if grad_F !=
// nullptr (Q1), grad_F[i] = the sum over the corners of the cell's i-th loop
// of d kappa_mod / d F (the centre gradients of the corrected lagged scheme,
// optim/lagged_objective.h).
double cell_energy_gradient(const MeshStencil& s, std::uint32_t c, Metric m,
                            std::span<const Point3> pts, double V0, double c_delta, Vec3* grad,
                            Vec3* grad_R = nullptr, Vec3* grad_F = nullptr);

}  // namespace polydual
