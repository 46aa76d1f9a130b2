// Stage composition shared by the subcommands: each step is timed and its
// record goes into the JSON summary (STYLE: every stage reports stats).
#pragma once
#include <chrono>
#include <string>
#include <vector>

#include "classify/classify.h"
#include "core/json.h"
#include "dual/build_dual.h"
#include "mesh/poly_mesh.h"
#include "quality/star_test.h"

namespace polydual::cli {

class Timer {
 public:
  Timer() : t0_(std::chrono::steady_clock::now()) {}
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
  }

 private:
  std::chrono::steady_clock::time_point t0_;
};

// Reads any supported tet mesh and classifies it; adds "read"/"classify" times.
ClassifiedTetMesh load_classified(const std::string& path, const ClassifyParams& params, Json& seconds);

// Counts of model entities and the model faces with their kinds.
Json model_summary(const ClassifiedTetMesh& mesh);

// Validation + exact star test summary of a polyhedral mesh; verdicts are
// returned for writing as cell data.
Json poly_summary(const PolyMesh& pm, const std::vector<CellVerdict>& verdicts,
                  const ClassifiedTetMesh* primal);

// Writes a PolyMesh as VTU (with valid/bad_tets cell data) or as an OpenFOAM
// case; returns the writer's record.
Json write_poly(const PolyMesh& pm, const std::vector<CellVerdict>& verdicts, const std::string& out,
                const std::string& format);

// "vtu" or "foam" from an explicit --format or the output path.
std::string output_format(const std::string& requested, const std::string& out);

}  // namespace polydual::cli
