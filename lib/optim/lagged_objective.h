// The lagged local objective of one point p: the corners of p's cells
// in which p is a corner vertex or an edge end, with the region centres R and
// face centres F held at their values when the visit starts. Moving p then
// changes only these corners (4 per face of p under Q1, 3 under Q2, against
// every corner of every cell of p in LocalObjective), so a visit costs a few
// dozen corner evaluations. The exact star test of the optimiser still uses the
// true centres, so the validity guarantee is unchanged; only the Newton model
// and the line search's decrease test see lagged centres.
//
// Corrected (the default scheme): the lagged model plus the linear term
// G . (x - x0), where G is what the held centres leave out of the gradient at
// the build position x0: sum over p's cells of (1/m) dE/dR and over p's faces of
// (1/k) dE/dF, from the centre gradients of every corner of those cells
// (cell_energy_gradient's grad_R, grad_F), taken at the start of the sweep. With
// current centre gradients the model's gradient at x0 is the true local
// objective's, so the scheme's fixed points are those of the full objective
// (proofs/quality.md §6b); only the model's curvature stays lagged.
#pragma once
#include <vector>

#include "quality/corner.h"
#include "quality/stencil.h"

namespace polydual {

class LaggedObjective {
 public:
  // Collects p's direct corners at the current positions pts. grad_R (per
  // cell) and grad_F (per loop of the stencil, Q1), both or neither: the centre
  // gradients of the correction term; null: the plain lagged model.
  void build(const MeshStencil& s, const Point3* pts, const double* V0, Metric m, PointId p,
             const Vec3* grad_R = nullptr, const Vec3* grad_F = nullptr);
  // Sum of kappa_mod over the direct corners with p at x (centres lagged), plus
  // the correction G . (x - x0).
  double value(const Point3& x, double c) const;
  // The same at p's build position, with gradient g (3) and Hessian H (3x3
  // row-major) with respect to p. At the build position the value equals the
  // sum of the same corners of LocalObjective bit for bit.
  double derivatives(const Point3& x, double c, double g[3], double H[9]) const;
  std::size_t num_corners() const { return corners_.size(); }

 private:
  // Corner edges e_i = u_i + a_i x, a_i in {-1, 0, 1}.
  struct Corner {
    Point3 u[3];
    double a[3];
    double v0;
  };
  static void corner_edges(const Corner& k, const Point3& x, double e[3][3]);
  void add(const Point3* P, const bool* is_p, const Point3& vertex, bool vertex_is_p, double v0);
  double correction(const Point3& x) const {
    return G_.x * (x.x - x0_.x) + G_.y * (x.y - x0_.y) + G_.z * (x.z - x0_.z);
  }
  std::vector<Corner> corners_;
  Vec3 G_{};     // the correction's gradient (zero for the plain lagged model)
  Point3 x0_{};  // p's build position
};

}  // namespace polydual
