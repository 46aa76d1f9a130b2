// The mutable tet mesh of the tet stage's topological operations (Delaunay
// flips, optim/tet_flip.h; interior point insertion, optim/steiner.h): tets by
// slot with adjacency and model-face tags, cavities replaced in place, and
// the ClassifiedTetMesh rebuilt at the end with the classification carried
// over (model-face triangles and constrained edges kept, new edges and
// triangles classified on their region, as classify() gives them).
#pragma once
#include <array>
#include <cstdint>
#include <deque>
#include <span>
#include <vector>

#include "mesh/classified_tet_mesh.h"
#include "predicates/predicates.h"

namespace polydual::tetops {

constexpr std::uint32_t kNone = UINT32_MAX;
constexpr std::int32_t kNoFace = TetMeshBuilder::kNoFace;
using Tet = std::array<std::uint32_t, 4>;

double tet_quality_of(const Point3& a, const Point3& b, const Point3& c, const Point3& d);

// The edges a flip may not remove: those classified on a model edge or face
// (dim < 3), by their (low, high) vertex pair, sorted for a binary search.
class ConstrainedEdges {
 public:
  explicit ConstrainedEdges(const ClassifiedTetMesh& m);
  // The classification of edge (a, b) if it is constrained, else nullptr.
  const ModelRef* find(std::uint32_t a, std::uint32_t b) const;

 private:
  struct Entry {
    std::uint64_t key;
    ModelRef ref;
  };
  static std::uint64_t key(std::uint32_t a, std::uint32_t b) {
    if (a > b) std::swap(a, b);
    return (std::uint64_t(a) << 32) | b;
  }
  std::vector<Entry> entries_;
};

struct Candidate {
  std::uint32_t tet, version;
  int face;
};

// The mutable mesh the flips work on: tets by slot, with adjacency (4 * slot
// + the neighbour's local face, kNone on the boundary) and the model-face tag
// of every local face (kNoFace when none).
struct FlipMesh {
  std::vector<Point3> pts;  // the mesh's points, then the points inserted (optim/steiner.h)
  std::vector<std::int32_t> new_vertex_region;  // per inserted point, its region
  std::vector<Tet> tv;
  std::vector<std::array<std::uint32_t, 4>> nb;
  std::vector<std::array<std::int32_t, 4>> ftag;
  std::vector<std::int32_t> region;
  std::vector<std::uint32_t> input_tet;
  std::vector<std::uint32_t> version;  // bumped whenever a slot is freed or refilled
  std::vector<std::uint8_t> alive;
  std::vector<std::uint32_t> free_slots;
  ConstrainedEdges cedges;
  std::deque<Candidate> queue;

  explicit FlipMesh(const ClassifiedTetMesh& m);
  const Point3& p(std::uint32_t v) const { return pts[v]; }
  Sign orient(const Tet& t) const { return orient3d(p(t[0]), p(t[1]), p(t[2]), p(t[3])); }
  double quality(const Tet& t) const { return tet_quality_of(p(t[0]), p(t[1]), p(t[2]), p(t[3])); }
  int local(std::uint32_t t, std::uint32_t v) const {
    for (int i = 0; i < 4; ++i)
      if (tv[t][i] == v) return i;
    return -1;
  }
};


// A local face's three vertices, sorted (a key to match faces).
std::array<std::uint32_t, 3> face_key(const Tet& t, int i);

struct OuterFace {
  std::array<std::uint32_t, 3> key;
  std::uint32_t link;  // 4 * outer tet + its local face, or kNone
  std::int32_t tag;
};

// The faces of the cavity `old` (tets being replaced) that stay: every face
// whose neighbour is not in the cavity, with its link and model-face tag.
std::vector<OuterFace> cavity_boundary(const FlipMesh& w, std::span<const std::uint32_t> old);

// Replaces the tets `old` (one region, one cavity) by `fresh` (all positive,
// same union): relinks the cavity's boundary faces with their tags, links the
// new interior faces (no model face) and queues the boundary faces.
void replace(FlipMesh& w, std::span<const std::uint32_t> old, std::span<const Tet> fresh);

// The ClassifiedTetMesh of w's live tets, in slot order: the classification
// of mesh's vertices, model-face triangles and constrained edges carried
// over; an inserted vertex is classified on its region, new edges on theirs,
// and it gets the input number after the last of mesh's. Throws InputError
// if the tets are not conformal.
ClassifiedTetMesh rebuild(const ClassifiedTetMesh& mesh, const FlipMesh& w);

}  // namespace polydual::tetops
