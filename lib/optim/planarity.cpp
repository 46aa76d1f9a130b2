#include "optim/planarity.h"

#include <cmath>

#include "quality/flatness.h"

namespace polydual::optim_detail {

void PlanarityTerm::build(const MeshStencil& s, PointId p) {
  loops_.clear();
  slot_.clear();
  for (std::uint32_t c : s.cells_of(p))
    for (std::uint32_t j = s.cell_loop_off[c]; j < s.cell_loop_off[c + 1]; ++j) {
      const auto loop = s.loop(j);
      for (std::size_t i = 0; i < loop.size(); ++i)
        if (loop[i] == p) {
          loops_.push_back(j);
          slot_.push_back(std::uint32_t(i));
          break;
        }
    }
}

double PlanarityTerm::value(const MeshStencil& s, const Point3* pts, const Point3& x) const {
  double sum = 0;
  for (std::size_t k = 0; k < loops_.size(); ++k) {
    const auto loop = s.loop(loops_[k]);
    poly_.clear();
    for (std::size_t i = 0; i < loop.size(); ++i) poly_.push_back(i == slot_[k] ? x : pts[loop[i].idx]);
    sum += double(loop.size()) * (1.0 - flatness_ratio(poly_));
  }
  return sum;
}

}  // namespace polydual::optim_detail
