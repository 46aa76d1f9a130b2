// What a reader or generator hands over: tets with region tags and whatever
// classification the source carried. classify() (lib/classify) validates it and
// turns it into a ClassifiedTetMesh.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/vec3.h"

namespace polydual {

struct TaggedTriangle {
  std::array<std::uint32_t, 3> v{};
  std::int32_t tag = 0;  // model face tag
};
struct TaggedEdge {
  std::array<std::uint32_t, 2> v{};
  std::int32_t tag = 0;  // model edge tag
};
struct TaggedVertex {
  std::uint32_t v = 0;
  std::int32_t tag = 0;  // model vertex tag
};

struct TetSoup {
  std::string source;                             // file name, for error messages
  std::vector<Point3> points;
  std::vector<std::array<std::uint32_t, 4>> tets;  // 0-based point indices
  std::vector<std::int32_t> tet_region;           // model region tag per tet
  // Optional classification carried by the source. Triangles: boundary,
  // interface and fracture triangles with their model face tag. Edges: primal
  // edges on model edges. Vertices: primal vertices on model vertices.
  std::vector<TaggedTriangle> triangles;
  std::vector<TaggedEdge> edges;
  std::vector<TaggedVertex> corners;
  // True when the source classifies every boundary/interface entity (Gmsh msh4
  // with $Entities): classify() then checks the given classification instead of
  // inferring it, and reports contradictions.
  bool full_classification = false;
};

}  // namespace polydual
