#include "fuzz_common.h"
#include "io/medit_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz_one([&] { return polydual::read_medit(as_text(data, size), "fuzz.mesh"); });
}
