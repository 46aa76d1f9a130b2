#include "classify/spatial_order.h"

#include <algorithm>
#include <numeric>
#include <utility>

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
  std::vector<std::uint64_t> keys(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Point3& p = points[i];
    auto q = [](double v, double l, double s) { return std::uint64_t(std::min(kCells, (v - l) * s)); };
    keys[i] = spread3(q(p.x, lo.x, sx)) | spread3(q(p.y, lo.y, sy)) << 1 | spread3(q(p.z, lo.z, sz)) << 2;
  }
  // Stable LSD radix sort of (key, index) on the 63 key bits, 11 bits a pass:
  // the order of std::sort on the pairs (equal keys keep index order), without
  // a comparison sort's unpredictable branches.
  constexpr int kBits = 11, kPasses = 6;
  constexpr std::size_t kBuckets = std::size_t(1) << kBits;
  std::vector<std::uint32_t> count(kPasses * kBuckets, 0);
  for (std::uint64_t k : keys)
    for (int r = 0; r < kPasses; ++r) ++count[r * kBuckets + ((k >> (kBits * r)) & (kBuckets - 1))];
  std::vector<std::uint64_t> keys2(n);
  std::vector<std::uint32_t> order2(n);
  for (int r = 0; r < kPasses; ++r) {
    std::uint32_t* c = count.data() + r * kBuckets;
    if (*std::max_element(c, c + kBuckets) == n) continue;  // one digit for all: nothing moves
    std::uint32_t sum = 0;
    for (std::size_t b = 0; b < kBuckets; ++b) sum += std::exchange(c[b], sum);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t pos = c[(keys[i] >> (kBits * r)) & (kBuckets - 1)]++;
      keys2[pos] = keys[i];
      order2[pos] = order[i];
    }
    keys.swap(keys2);
    order.swap(order2);
  }
  return order;
}

}  // namespace polydual
