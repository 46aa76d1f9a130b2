// Typed index handles with a named invalid value (docs/design.md, Conventions: no raw ids, no magic -1).
#pragma once
#include <compare>
#include <cstdint>
#include <functional>
#include <limits>

namespace polydual {

template <class Tag>
struct Handle {
  static constexpr std::uint32_t kInvalid = std::numeric_limits<std::uint32_t>::max();
  std::uint32_t idx = kInvalid;

  constexpr Handle() = default;
  constexpr explicit Handle(std::uint32_t i) : idx(i) {}
  constexpr explicit Handle(std::size_t i) : idx(static_cast<std::uint32_t>(i)) {}
  constexpr explicit Handle(int i) : idx(static_cast<std::uint32_t>(i)) {}
  static constexpr Handle invalid() { return Handle(); }
  constexpr bool valid() const { return idx != kInvalid; }
  constexpr explicit operator std::size_t() const { return idx; }
  friend constexpr auto operator<=>(Handle, Handle) = default;
};

// Primal (input tet mesh) entities.
using VertexId = Handle<struct VertexTag>;
using EdgeId = Handle<struct EdgeTag>;
using TriId = Handle<struct TriTag>;
using TetId = Handle<struct TetTag>;
// Dual (polyhedral mesh) entities.
using PointId = Handle<struct PointTag>;
using FaceId = Handle<struct FaceTag>;
using CellId = Handle<struct CellTag>;

// A half-face: face f seen from one of its two cells. side 0 = the owner, whose
// outward normal the face's vertex loop follows (right-hand rule); side 1 = the
// neighbour, which sees the loop reversed. Opposite half-face = h ^ 1.
struct HalfFace {
  std::uint32_t code = Handle<void>::kInvalid;
  constexpr HalfFace() = default;
  constexpr HalfFace(FaceId f, int side) : code(2u * f.idx + static_cast<std::uint32_t>(side)) {}
  constexpr FaceId face() const { return FaceId(code >> 1); }
  constexpr int side() const { return static_cast<int>(code & 1u); }
  constexpr HalfFace opposite() const { HalfFace h; h.code = code ^ 1u; return h; }
  friend constexpr auto operator<=>(HalfFace, HalfFace) = default;
};

}  // namespace polydual

template <class Tag>
struct std::hash<polydual::Handle<Tag>> {
  std::size_t operator()(polydual::Handle<Tag> h) const noexcept { return h.idx; }
};
