// One fuzz input holds the three TetGen files separated by NUL bytes:
// node \0 ele [\0 face] (run.sh builds the seeds that way).
#include "fuzz_common.h"
#include "io/tetgen_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view all = as_text(data, size);
  const std::size_t a = all.find('\0');
  const std::string_view node = all.substr(0, a);
  const std::string_view rest = a == std::string_view::npos ? std::string_view() : all.substr(a + 1);
  const std::size_t b = rest.find('\0');
  const std::string_view ele = rest.substr(0, b);
  std::optional<std::string_view> face;
  if (b != std::string_view::npos) face = rest.substr(b + 1);
  return fuzz_one([&] { return polydual::read_tetgen(node, ele, face, "fuzz"); });
}
