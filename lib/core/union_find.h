// Disjoint sets with path halving and union by index (deterministic roots:
// the smaller index becomes the root, so component order follows input order).
#pragma once
#include <cstdint>
#include <numeric>
#include <vector>

namespace polydual {

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0u); }
  std::uint32_t find(std::size_t x) {
    std::uint32_t i = static_cast<std::uint32_t>(x);
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void unite(std::size_t a, std::size_t b) {
    std::uint32_t ra = find(a), rb = find(b);
    if (ra == rb) return;
    if (ra < rb) parent_[rb] = ra; else parent_[ra] = rb;
  }

 private:
  std::vector<std::uint32_t> parent_;
};

}  // namespace polydual
