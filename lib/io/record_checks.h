// Checks on single element records that every reader applies, so the error
// names the line or byte of the record instead of surfacing later (or not at
// all) in classify(). Tets with a repeated vertex are left to classify(),
// which reports them as zero-volume tets.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace polydual::io {

// "" when the N vertices are distinct, else a message naming the repeated one
// (0-based index shown 1-based, as in the files).
template <std::size_t N>
std::string repeated_vertex(const std::array<std::uint32_t, N>& v, const char* what) {
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (v[i] == v[j]) return std::string(what) + " has a repeated vertex (" + std::to_string(v[i] + 1) + ")";
  return {};
}

}  // namespace polydual::io
