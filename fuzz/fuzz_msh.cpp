#include "fuzz_common.h"
#include "io/msh_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz_one([&] { return polydual::read_msh(as_text(data, size), "fuzz.msh"); });
}
