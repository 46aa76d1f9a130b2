// Shared harness of the reader fuzzers: read the input with the memory
// reader, then classify() it (the path every input takes in the tool). Input
// and usage errors are the expected answers to bad input; any other exception
// escapes and libFuzzer reports it as a crash, as do sanitizer findings.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "classify/classify.h"
#include "core/error.h"

template <class Read>
int fuzz_one(Read read) {
  try {
    const polydual::TetSoup soup = read();
    polydual::classify(soup);
  } catch (const polydual::InputError&) {
  } catch (const polydual::UsageError&) {
  }
  return 0;
}

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}
