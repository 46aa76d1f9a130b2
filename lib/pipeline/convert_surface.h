// The pipeline of a surface mesh or surface network (design §15):
//   read -> build_primal (classification; degenerate cells refused, exactly)
//   -> surface dual (dual/surface_dual.h) -> smooth (optim/surface_smooth.h;
//   sweeps 0: none) -> check (exact fan test and the area identity,
//   quality/surface_verdict.h) -> split, when a polygon is invalid
//   (split/surface_split.h) -> write (a SurfaceWriter of
//   io/format_registry.h).
// Nothing here prints or exits.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "core/json.h"
#include "io/format_registry.h"
#include "io/write_context.h"
#include "mesh/poly_surface.h"
#include "mesh/primal_mesh.h"
#include "mesh/tet_soup.h"
#include "optim/surface_smooth.h"
#include "pipeline/convert.h"
#include "quality/surface_verdict.h"

namespace polydual {

struct SurfaceConvertResult {
  PrimalMesh primal;
  PolySurface dual;
  SurfaceVerdicts verdicts;
  SurfaceAreaIdentity areas;
  SurfaceSmoothReport smooth;
  ConvertReport report;  // stages "primal", "dual", "smooth", "check", ["split"], "write" (file entry)
  Json split;            // the split stage's record (null: it did not run)
  Json written;          // the writer's record (file entry)
  std::vector<std::string> warnings;
};

struct SurfaceConvertParams {
  SurfaceSmoothParams smooth;
  // The split (split/surface_split.h): rounds of whole cuts at the vertices
  // of invalid polygons, at most split_rounds (--no-split: off).
  bool split = true;
  int split_rounds = SplitParams{}.max_rounds;
  // Refuse (InputError naming the polygons, nothing written) a dual with a
  // polygon the exact fan test finds invalid (--require-valid).
  bool require_valid = false;
};

// The surface pipeline's parameters that follow a volume run's: smoothing
// unless the optimiser is off or only untangles (the dual points then stay
// where Algorithm 1 puts them), the split and its rounds, and --require-valid.
SurfaceConvertParams surface_params(const PipelineParams& params);

// Whether a soup is a surface mesh: no volume cell, some triangle or quadrangle.
bool is_surface_soup(const TetSoup& soup);

// soup -> primal -> dual -> check. InputError naming the source and the
// place for a bad mesh (degenerate cell, inconsistent orientation).
SurfaceConvertResult convert_surface(const TetSoup& soup, const SurfaceConvertParams& params = {},
                                     const ConvertHooks& hooks = {});

// The invalid polygons, at most `limit`: "polygon P (vertex V, surface T)",
// V in the input numbering (1-based).
std::vector<std::string> invalid_polygon_items(const SurfaceConvertResult& r, std::size_t limit);

// The cell arrays written with the dual: "valid" (Int32, 1 or 0).
Json write_surface_result(const SurfaceConvertResult& r, const std::string& path, const SurfaceWriter& writer,
                          const PolyWriteOptions& options = {});

// File to file: the output is checked first (io/output_guard.h: never an
// input, an existing file only with the writer's extension unless --force),
// then `soup` (read from `in` by the caller, a surface soup) is converted and
// written atomically. `format`: the `--format` value ("" = by extension);
// a volume format ("foam") is a UsageError before any work.
SurfaceConvertResult convert_surface_file(TetSoup soup, const std::string& in, const std::string& out,
                                          std::string_view format, const SurfaceConvertParams& params = {},
                                          const PolyWriteOptions& options = {}, const ConvertHooks& hooks = {});

// The machine-readable summary: counts, invalid polygons, the area identity
// and the stages.
Json surface_summary(const SurfaceConvertResult& r);

}  // namespace polydual
