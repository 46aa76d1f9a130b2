// Classification of a mesh entity on the geometric model (design §1): the
// dimension and tag of the lowest-dimension model entity it lies on.
#pragma once
#include <compare>
#include <cstdint>

namespace polydual {

struct ModelRef {
  static constexpr std::int8_t kNone = -1;
  std::int8_t dim = kNone;  // 0 vertex, 1 edge, 2 face, 3 region, -1 unclassified
  std::int32_t tag = 0;
  constexpr bool valid() const { return dim >= 0; }
  friend constexpr auto operator<=>(ModelRef, ModelRef) = default;
};

// What a face lies on: inside one region, or on a model face, named from the
// regions on the model face's two sides (ModelTopology::face_kind).
enum class FaceKind : std::uint8_t {
  Interior = 0,   // inside one region, not on a model face
  External = 1,   // on an external model face (owner only)
  Interface = 2,  // on a model face between two regions
  Fracture = 3,   // on a model face with the same region on both sides
};

}  // namespace polydual
