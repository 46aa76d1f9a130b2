// Classification (design §3): validates a TetSoup and produces the
// ClassifiedTetMesh, inferring the model's faces, edges and vertices where the
// source gave only region tags or face markers (a marker is split at sharp
// edges by the feature angle and stays the source_tag of its model faces), or
// checking the given classification against the mesh topology when the
// source gave it all (Gmsh msh4): what it lacks (curves, points) is inferred
// with fresh tags above the file's and reported in
// ClassifiedTetMesh::classification_warnings(); contradictions are errors.
#pragma once
#include <string>

#include "core/json.h"

#include "mesh/classified_tet_mesh.h"
#include "mesh/tet_soup.h"

namespace polydual {

struct ClassifyParams {
  // Dihedral angle (degrees) between neighbouring model-face triangles above
  // which a model face is split (and between model-edge segments above which a
  // model vertex is made). Applies to untagged model faces and inside given
  // face markers, not to a full classification's surfaces. Range (0, 180]: 0
  // excluded (every bend would split); 180 disables geometric splitting.
  // An edge bending above it is only a candidate: it splits model faces when
  // it is a feature (classify/features.h): above the strong angle, or in a
  // chain of consistently sharp edges, not isolated or zigzag facets of a
  // coarse curved surface.
  double feature_angle_deg = 30.0;
  static constexpr double kMinFeatureAngleDeg = 0.0;  // excluded
  static constexpr double kMaxFeatureAngleDeg = 180.0;
  // Dihedral bend (degrees) above which an edge is always a feature, and a
  // turn of a model edge above which its vertex is always a corner (the
  // larger of this and feature_angle_deg applies). Range (0, 180].
  double strong_angle_deg = 60.0;
  // A chain of consistently sharp edges this long (in primal edges) is a
  // feature line; shorter ones only when they join features at both ends.
  // Range [1, 1e6].
  std::size_t min_feature_chain_edges = 3;

  // Throws UsageError naming the field, its unit and its allowed range.
  void validate() const;
  Json to_json() const;
};

// Wall-clock seconds of classify()'s stages (for benchmarks and --json).
struct ClassifyStats {
  double seconds_validate = 0;        // indices, finite coordinates, exact orientation
  double seconds_order = 0;           // spatial renumbering
  double seconds_topology = 0;        // adjacency, triangles, edges, stars
  double seconds_overlap = 0;         // coincident vertices, overlapping parts (classify/self_overlap.h)
  double seconds_classification = 0;  // model faces, edges, vertices
  Json to_json() const;
};

// Validates on load (design §2): finite coordinates, indices in range, every tet
// positively oriented by the exact predicate (zero-volume tets, and tets
// oriented against the others, are errors naming the tets; a mesh whose tets
// are all negatively oriented is flipped whole, with a warning in
// classification_warnings()), conformity, unused vertices, no two vertices at
// one place and no part overlapping another (classify/self_overlap.h). Throws
// InputError naming soup.source and the place (also for the contradictions of
// a full classification: a triangle on two surfaces, a boundary or interface
// triangle on none, a curve whose edges lie on different surfaces);
// UsageError if params do not validate().
ClassifiedTetMesh classify(const TetSoup& soup, const ClassifyParams& params = {},
                           ClassifyStats* stats = nullptr);

}  // namespace polydual
