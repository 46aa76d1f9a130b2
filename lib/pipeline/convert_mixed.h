// Internal to lib/pipeline: the stages of a mixed soup (tets, pyramids,
// prisms, hexahedra; design §14) from build_primal to the last check, as
// the tet pipeline's (convert.cpp) without free-edge cuts, and with the mixed
// split: whole cuts only (dual/primal_dual.h).
#pragma once
#include <array>
#include <cstdint>

#include "mesh/primal_mesh.h"
#include "mesh/tet_soup.h"
#include "mesh/validate.h"
#include "pipeline/convert.h"

namespace polydual::pipeline_detail {

// classify (build_primal), dual, cleanup, cells, check, optimize (the
// primal's ModelFacets), check_after, and when params.split.enabled and the
// optimiser runs, the "split" stage: rounds (at most split.max_rounds) that
// cut whole the primal vertices of the cells still invalid, rebuild the dual
// with the optimised points kept where no cut touches them, re-optimise
// around the cuts and check; they stop when no cell is invalid or a round
// cuts no new vertex (split/mixed_split.h); then check_split validates the
// mesh kept. Sets r.mixed, r.mesh, r.check and the report's invalid_before. InputError for a surface mesh (no volume cell).
void run_mixed_stages(ConvertResult& r, const TetSoup& soup, const PipelineParams& params, const ConvertHooks& hooks);

// The class of the primal vertex with input number `in` (PolyMesh::cell_primal),
// or ModelRef{} when the primal has none.
ModelRef mixed_vertex_class(const PrimalMesh& m, std::uint64_t in);

}  // namespace polydual::pipeline_detail
