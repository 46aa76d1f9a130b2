// Stable LSD radix sort by an unsigned integer key, 8 bits a pass (passes
// where every key has the same digit are skipped). For the record lists that
// are sorted in the hot path: a comparison sort's branches there are coin
// tosses, and the records are generated in the tie order already (stable).
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace polydual {

// key(x) -> an unsigned integer below 2^key_bits.
template <class T, class Key>
void radix_sort_by_key(std::vector<T>& v, Key&& key, int key_bits) {
  const std::size_t n = v.size();
  if (n < 2) return;
  std::vector<T> tmp(n);
  for (int shift = 0; shift < key_bits; shift += 8) {
    std::array<std::uint32_t, 256> count{};
    for (const T& x : v) ++count[(key(x) >> shift) & 255u];
    if (*std::max_element(count.begin(), count.end()) == n) continue;  // one digit for all
    std::uint32_t sum = 0;
    for (std::uint32_t& c : count) {
      const std::uint32_t k = c;
      c = sum;
      sum += k;
    }
    for (const T& x : v) tmp[count[(key(x) >> shift) & 255u]++] = x;
    v.swap(tmp);
  }
}

}  // namespace polydual
