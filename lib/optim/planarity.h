// The face-flatness term of the local objective (the paper's future work:
// `--planarity W`, OptimParams::planarity). For a point p it sums,
// over the loops of p's cells that contain p (an interior face twice, once per
// cell, a boundary face once), n_j * (1 - flatness_j): flatness_j is OpenFOAM's
// face flatness (projected over actual area of the fan around its
// area-weighted centre, quality/flatness.h flatness_ratio), n_j the loop's
// number of points, so the penalty is scaled per corner like the kappa sum. Inexact (a
// floating-point objective, like kappa): it decides nothing; every move is
// still accepted only if the exact star test keeps the valid cells valid.
#pragma once
#include <cstdint>
#include <vector>

#include "core/vec3.h"
#include "quality/stencil.h"

namespace polydual::optim_detail {

class PlanarityTerm {
 public:
  // The loops around p (indices into the stencil's loops) and p's slot in each.
  void build(const MeshStencil& s, PointId p);
  // The term with p at x, the other points at pts.
  double value(const MeshStencil& s, const Point3* pts, const Point3& x) const;
  bool empty() const { return loops_.empty(); }

 private:
  std::vector<std::uint32_t> loops_, slot_;
  mutable std::vector<Point3> poly_;  // scratch: one loop with p at x
};

}  // namespace polydual::optim_detail
