// The feature-angle split of a mixed mesh's inferred model faces (design §3
// for tets, §14): build_primal() puts every boundary or interface face the
// file did not tag on one model face per pair of regions, so a box whose
// file names only its volumes has one curved model face and no model edges,
// and the dual's caps cut its corners. Here those inferred model faces are
// cut along their feature edges (classify/features.h's rule: sharp above the
// feature angle and kept as a line, or above the strong angle) and into
// connected parts, each given its own tag as if the file had tagged it.
// Faces the file tagged are kept as they are. Double geometry: an angle
// threshold is a modelling choice, not a sign (proofs/classification.md L15).
#pragma once
#include <cstddef>

#include "mesh/cell_soup.h"
#include "mesh/primal_mesh.h"

namespace polydual {

// Appends to soup.faces every face of m on an inferred model face (tags not
// among soup.faces'), tagged by its part (fresh tags above every face tag of
// soup and m, numbered by first face); returns how many parts. m must be
// build_primal(soup). Rebuilding the primal from soup then classifies the
// parts' boundaries as model edges and vertices.
std::size_t tag_inferred_model_faces(CellSoup& soup, const PrimalMesh& m, double feature_angle_deg);

}  // namespace polydual
