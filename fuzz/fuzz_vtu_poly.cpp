// The polyhedron VTU reader (what `polydual check` and `optimize` read), then
// validate() on what it returns. Input errors are the expected answers; any
// other exception or a sanitizer finding is a crash.
#include "fuzz_common.h"
#include "io/vtu_poly_reader.h"
#include "mesh/validate.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const polydual::PolyMesh mesh = polydual::read_vtu_poly_bytes(as_text(data, size), "fuzz.vtu");
    polydual::validate(mesh);
  } catch (const polydual::InputError&) {
  }
  return 0;
}
