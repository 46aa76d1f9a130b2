// Cleanup of the draft dual (design §4 step 9, paper §2.8): merge the points the
// builder found to coincide exactly, collapse short edges between points of the
// same classification, rewrite face loops, drop faces that degenerate below
// three distinct points, and drop points no face uses. Reads and writes only
// the draft: its mesh (points and faces; cells are not assembled yet) and its
// hints.
#pragma once
#include <cstddef>

#include "core/json.h"
#include "dual/dual_draft.h"

namespace polydual {

struct CleanupStats {
  std::size_t merged_points = 0;     // by the exact coincidences (exact_pairs)
  std::size_t collapsed_points = 0;  // by the short-edge collapse
  std::size_t dropped_faces = 0;     // faces left with fewer than 3 distinct points
  std::size_t dropped_points = 0;    // points no face uses any more
  double seconds = 0;
  Json to_json() const;
};

// The collapse length and the pairs to look at are the draft's
// (DualDraft::collapse_length, exact_pairs, short_pairs, scan_faces): the
// builder found them for its DualParams. Points merged into one keep the
// coordinates, classification and origin (PolyMesh::point_origin, kept
// aligned with the points when present) of the smallest id; a point whose
// classification is of another dimension than its origin (what cuts add,
// build_dual.h) is never collapsed; points and faces keep
// their relative order. Works in place, without a second mesh (the cleanup
// runs at the memory peak of the dual construction). The hints are consumed
// (left empty).
CleanupStats cleanup_dual(DualDraft& draft);

}  // namespace polydual
