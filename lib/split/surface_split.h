// The split of a surface dual (design §15): rounds of whole cuts at the
// primal vertices of the polygons the exact fan test rejects. A vertex cut
// whole has one polygon per cell around it, the cell's barycentric corner
// (dual/surface_dual.h), valid by construction for a non-degenerate cell;
// each round rebuilds the dual with every cut so far, keeps the smoothed
// central points of the cells no cut touches, smooths again (the smoother
// never makes a valid polygon invalid) and checks. A neighbour that a cut's
// moved points make invalid is cut in the next round, so the rounds end with
// every polygon valid, at worst with every vertex cut (proofs/surface_dual.md S3).
#pragma once
#include <functional>
#include <vector>

#include "core/json.h"
#include "mesh/poly_surface.h"
#include "mesh/primal_mesh.h"
#include "quality/surface_verdict.h"
#include "split/split.h"

namespace polydual {

// Smooths a rebuilt dual in place (the surface smoother, or nothing).
using SurfaceSmoother = std::function<void(PolySurface&)>;

// `dual` is m's surface dual as smoothed, `verdicts` its exact verdicts. On
// return both are the last round's. Stops when no polygon is invalid, a
// round cuts no new vertex, or after params.max_rounds rounds. Returns the
// stage's record (rounds, whole_vertices, invalid and polygons before and
// after). Throws Interrupted between rounds.
Json run_surface_split(const PrimalMesh& m, const SplitParams& params, const SurfaceSmoother& smooth,
                       PolySurface& dual, SurfaceVerdicts& verdicts);

// The central points of `after`'s cells that touch no vertex marked in
// `whole` take their positions in `before` (a dual of the same primal):
// the smoothing done before the cut is kept. Returns the points moved.
std::size_t warm_start_surface(const PrimalMesh& m, const std::vector<char>& whole, const PolySurface& before,
                               PolySurface& after);

}  // namespace polydual
