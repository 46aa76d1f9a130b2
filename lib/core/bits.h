// Bit counting without a library call. The default x86-64 target has no
// POPCNT instruction, and std::popcount then calls libgcc's __popcountdi2
// through the PLT; rank queries sit in hot loops (tet_triangle, dual point
// ids), so the portable SWAR count is used unless the target has POPCNT.
#pragma once
#include <bit>
#include <cstdint>

namespace polydual {

inline int popcount64(std::uint64_t x) {
#if defined(__POPCNT__)
  return std::popcount(x);
#else
  x = x - ((x >> 1) & 0x5555555555555555ull);
  x = (x & 0x3333333333333333ull) + ((x >> 2) & 0x3333333333333333ull);
  x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0full;
  return int((x * 0x0101010101010101ull) >> 56);
#endif
}

}  // namespace polydual
