#include "classify/spatial_order.h"

#include <algorithm>
#include <numeric>

#include "core/radix_sort.h"

namespace polydual {

namespace {
// Spreads the low 21 bits of x to every third bit.
std::uint64_t spread3(std::uint64_t x) {
  x &= 0x1fffffULL;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}
}  // namespace

std::vector<std::uint32_t> morton_order(const std::vector<Point3>& points) {
  const std::size_t n = points.size();
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  if (n < 2) return order;
  Point3 lo = points[0], hi = points[0];
  for (const Point3& p : points) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  static constexpr double kCells = double((1u << 21) - 1);
  auto scale = [&](double l, double h) { return h > l ? kCells / (h - l) : 0.0; };
  const double sx = scale(lo.x, hi.x), sy = scale(lo.y, hi.y), sz = scale(lo.z, hi.z);
  struct Keyed { std::uint64_t key; std::uint32_t index; };
  std::vector<Keyed> keys(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Point3& p = points[i];
    auto q = [](double v, double l, double s) { return std::uint64_t(std::min(kCells, (v - l) * s)); };
    keys[i] = {spread3(q(p.x, lo.x, sx)) | spread3(q(p.y, lo.y, sy)) << 1 | spread3(q(p.z, lo.z, sz)) << 2,
               std::uint32_t(i)};
  }
  // Stable radix sort on the 63 key bits: the order of std::sort on (key,
  // index) pairs, without a comparison sort's unpredictable branches.
  radix_sort_by_key(keys, [](const Keyed& k) { return k.key; }, 63);
  for (std::size_t i = 0; i < n; ++i) order[i] = keys[i].index;
  return order;
}

}  // namespace polydual
