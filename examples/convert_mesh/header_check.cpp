// Compiled in its own translation unit: pipeline/convert.h (with all it
// includes) is self-contained against the installed include directory.
#include "pipeline/convert.h"

namespace convert_mesh_example {

// Names the entry so the header is used, not only parsed.
[[maybe_unused]] const auto convert_entry = &polydual::convert;

}  // namespace convert_mesh_example
