// `convert` (tet mesh -> dual -> optimise -> VTU / OpenFOAM) and `check`
// (a polyhedral VTU's validation and exact verdicts).
#include <cstdio>

#include "cli/commands.h"
#include "cli/print.h"
#include "core/error.h"
#include "core/stopwatch.h"
#include "io/format_registry.h"
#include "io/read_any_mesh.h"
#include "io/vtu_poly_reader.h"
#include "pipeline/convert.h"
#include "pipeline/convert_surface.h"
#include "pipeline/summary.h"

namespace polydual::cli {

const CommandSpec kConvert{
    "convert", "convert IN -o OUT [--format " + poly_format_choices() + "] [options]",
    "Builds the polyhedral dual of a classified tet mesh (paper Algorithm 1), checks\n"
    "every cell with the exact star-shaped test, untangles and smooths it, and writes\n"
    "VTU (VTK_POLYHEDRON) or an OpenFOAM case directory (OUT/constant/polyMesh).\n"
    "IN is read by its extension: " + mesh_extensions_text() + ".\n"
    "A Gmsh mesh of surfaces alone (a fracture network) gives its surface dual:\n"
    "one polygon per side of each vertex, checked exactly, smoothed within the\n"
    "surfaces (not with --optimize none), written as VTU of VTK_POLYGON cells.",
    1, 1,
    {"-o", "--format", "--force", "--vtu-encoding", "--zlib", "--feature-angle", "--strong-angle", "--boundary", "--no-cleanup", "--collapse-tol", "--optimize", "--planarity", "--no-optimize-tets", "--optimize-tets", "--tet-sweeps", "--tet-flips", "--interior-points", "--tet-flip-rounds", "--no-split", "--split-rounds", "--no-coarsen", "--require-valid", "--metric",
     "--derivatives", "--relaxation", "--tol", "--polish-sweeps", "--polish-share", "--worst-rounds", "--settle-move", "--max-iter", "--threads", "--json", "--quiet"}};

const CommandSpec kCheck{
    "check", "check FILE.vtu [--json] [--threads N] [--quiet]",
    "Re-reads a polyhedral VTU written by polydual and reports the topological\n"
    "validation (closed cells, faces) and the exact star-shaped verdicts. Exits 1,\n"
    "naming the failed checks and their cells on stderr, when the mesh is not sound\n"
    "(topology_ok or geometry_ok false); invalid (non-star-shaped) cells are reported,\n"
    "not failed.",
    1, 1,
    {"--threads", "--json", "--quiet"}};

namespace {

// The dual of a surface mesh (pipeline/convert_surface.h): polygons.
int convert_surface_mesh(const Settings& s, TetSoup soup) {
  ProgressPrinter progress(s.quiet);
  const SurfaceConvertParams params = surface_params(s.params);
  const SurfaceConvertResult r = convert_surface_file(std::move(soup), s.positional[0], s.out, s.format, params,
                                                      s.write, progress.hooks());
  progress.end_line();
  print_warnings(r.warnings, s.quiet);
  const Json summary = surface_summary(r);
  if (s.json) print_json(summary);
  else if (!s.quiet)
    std::printf("%s: surface dual of %zu cells: %zu polygons, %zu points, %zu invalid; area identity on %zu planar "
                "surface(s): max relative error %.3g (all %zu surfaces: %.3g); smoothing moved %zu points, min fan "
                "quality %.3g -> %.3g; %.3f s\n",
                s.out.c_str(), r.primal.num_cells(), r.dual.num_polygons(), r.dual.num_points(), r.verdicts.invalid,
                r.areas.planar, r.areas.max_rel_error, r.areas.surfaces.size(), r.areas.max_rel_error_all,
                r.smooth.moved, r.smooth.min_quality_before, r.smooth.min_quality_after, r.report.seconds);
  if (!s.json && !s.quiet && r.split.find("rounds"))
    std::printf("  split: %s rounds, %s vertices cut whole, invalid polygons %s -> %s, polygons %s -> %s\n",
                r.split.find("rounds")->dump().c_str(), r.split.find("whole_vertices")->dump().c_str(),
                r.split.find("invalid_before")->dump().c_str(), r.split.find("invalid_after")->dump().c_str(),
                r.split.find("polygons_before")->dump().c_str(), r.split.find("polygons_after")->dump().c_str());
  if (r.verdicts.invalid > 0) {
    const Defect d{"invalid_polygons", "polygons not star-shaped about their primal vertex", r.verdicts.invalid,
                   invalid_polygon_items(r, 10)};
    print_defects("convert", "warning", s.out + " written with polygons that are not star-shaped (--require-valid "
                                        "refuses it):", {d});
  }
  return 0;
}

int convert_volume_mesh(const Settings& s) {
  const PolyFormat format = poly_format_for(s.format, s.out);
  ProgressPrinter progress(s.quiet);
  const ConvertResult r = convert_file(s.positional[0], s.out, format, s.params, progress.hooks(), s.write);
  progress.end_line();
  print_warnings(r.warnings, s.quiet);
  const Json summary = convert_summary(r, s.params);
  if (s.json) print_json(summary);
  else print_convert_summary(summary);
  if (const std::vector<Defect> defects = r.check.validation.defects(); !defects.empty())
    print_defects("convert", "warning", s.out + " written, but the dual is not sound (--require-valid refuses it):",
                  defects);
  if (const Defect invalid = invalid_cells_defect(r); invalid.count > 0)
    print_defects("convert", "warning", s.out + " written with cells that are not star-shaped (--require-valid refuses it):",
                  {invalid});
  return 0;
}

}  // namespace

int cmd_convert(const Settings& s) {
  if (s.out.empty()) throw UsageError("convert needs -o OUT");
  try {
    return convert_volume_mesh(s);
  } catch (const InputError&) {
    // A mesh of surfaces alone (no volume cell), which the volume readers
    // refuse, converts to the polygons of its surface dual; the tet path is
    // left as it was and pays no second read.
    TetSoup soup = read_any_mesh(s.positional[0]);
    if (!is_surface_soup(soup)) throw;
    return convert_surface_mesh(s, std::move(soup));
  }
}

int cmd_check(const Settings& s) {
  const Stopwatch clock;
  const PolyMesh pm = read_vtu_poly(s.positional[0]);
  const CheckResult c = check_mesh(pm, nullptr);
  Json j = mesh_summary(pm, c, nullptr);
  j.set("file", s.positional[0]);
  j.set("seconds", clock.seconds());
  if (s.json) {
    print_json(j);
  } else {
    std::printf("%s: %zu cells, %zu faces, %zu points\n", s.positional[0].c_str(), pm.num_cells(),
                pm.num_faces(), pm.num_points());
    std::printf("%s\n", j.dump(0).c_str());
  }
  const std::vector<Defect> defects = c.validation.defects();
  if (defects.empty()) return 0;
  print_defects("check", "error", s.positional[0] + ": not a sound mesh (topology_ok " +
                                      (c.validation.ok() ? "true" : "false") + ", geometry_ok " +
                                      (c.validation.geometry_ok() ? "true" : "false") + "):",
                defects);
  return 1;
}

}  // namespace polydual::cli
