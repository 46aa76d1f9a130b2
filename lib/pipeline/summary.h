// Machine-readable summaries of pipeline results (the `--json` outputs and
// summary.json of the demo): one place for their keys, which the experiments
// (experiments/run.py) and benchmarks read.
#pragma once
#include "core/json.h"
#include "mesh/classified_tet_mesh.h"
#include "pipeline/check.h"
#include "pipeline/convert.h"

namespace polydual {

// {"points", "curves", "surfaces", "elements"}: what a reader dropped.
Json ignored_summary(const IgnoredEntities& ignored);

// Counts of model entities and the model faces with their kinds.
Json model_summary(const ClassifiedTetMesh& mesh);

// Counts, invalid cells and where they sit (by the class of their primal
// vertex, when the primal is known), per-material volumes, model coverage,
// the validation's failed checks ("defects", ValidationReport::defects), face flatness (measured here unless `flatness`, of this mesh, is given).
Json mesh_summary(const PolyMesh& mesh, const CheckResult& check, const ClassifiedTetMesh* primal,
                  const FlatnessStats* flatness = nullptr);

// The whole convert record: input sizes, model, mesh summary, invalid cells
// before/after, every stage's stats and seconds, the params.
Json convert_summary(const ConvertResult& r, const PipelineParams& params);

}  // namespace polydual
