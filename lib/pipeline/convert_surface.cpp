// The surface pipeline's stages (convert_surface.h).
#include "pipeline/convert_surface.h"

#include <sys/resource.h>

#include "classify/classify_primal.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "core/stopwatch.h"
#include "dual/surface_dual.h"
#include "io/output_guard.h"
#include "mesh/cell_soup.h"
#include "split/surface_split.h"

namespace polydual {
namespace {

double peak_rss() {
  rusage u{};
  return getrusage(RUSAGE_SELF, &u) == 0 ? double(u.ru_maxrss) / 1024.0 : 0.0;
}

template <class F>
auto stage(ConvertReport& report, const ConvertHooks& hooks, const char* name, F&& f) {
  throw_if_interrupted();
  const Stopwatch clock;
  Json stats = Json::object();
  auto value = f(stats);
  report.stages.push_back(StageRecord{name, clock.seconds(), std::move(stats), peak_rss()});
  report.seconds += report.stages.back().seconds;
  if (hooks.stage_done) hooks.stage_done(report.stages.back());
  return value;
}

Json area_json(const SurfaceAreaIdentity& a) {
  Json j = Json::object();
  j.set("planar_surfaces", a.planar);
  j.set("max_rel_error", a.max_rel_error);
  j.set("max_rel_error_all", a.max_rel_error_all);
  Json per = Json::array();
  for (const auto& [tag, s] : a.surfaces) {
    Json x = Json::object();
    x.set("surface", tag);
    x.set("planar", s.planar);
    x.set("primal", s.primal);
    x.set("dual", s.dual);
    per.push(std::move(x));
  }
  j.set("surfaces", std::move(per));
  return j;
}

}  // namespace

SurfaceConvertParams surface_params(const PipelineParams& params) {
  SurfaceConvertParams sp;
  const auto method = params.optim.method;
  if (method == OptimParams::Method::None || method == OptimParams::Method::Untangle) sp.smooth.sweeps = 0;
  sp.require_valid = params.split.require_valid;
  sp.split = params.split.enabled;
  sp.split_rounds = params.split.max_rounds;
  return sp;
}

bool is_surface_soup(const TetSoup& soup) {
  return soup.tets.empty() && soup.other_cells.empty() && !(soup.triangles.empty() && soup.quads.empty());
}

SurfaceConvertResult convert_surface(const TetSoup& soup, const SurfaceConvertParams& params,
                                     const ConvertHooks& hooks) {
  SurfaceConvertResult r;
  r.primal = stage(r.report, hooks, "primal", [&](Json& st) {
    PrimalMesh m = build_primal(cell_soup(soup), &r.warnings);
    st.set("cells", m.num_cells());
    st.set("vertices", m.num_vertices());
    st.set("edges", m.num_edges());
    return m;
  });
  r.dual = stage(r.report, hooks, "dual", [&](Json& st) {
    PolySurface d = build_surface_dual(r.primal);
    st.set("polygons", d.num_polygons());
    st.set("points", d.num_points());
    return d;
  });
  r.smooth = stage(r.report, hooks, "smooth", [&](Json& st) {
    SurfaceSmoothReport sm = smooth_surface(r.dual, r.primal, params.smooth);
    st.set("sweeps", sm.sweeps);
    st.set("moved", sm.moved);
    st.set("min_quality_before", sm.min_quality_before);
    st.set("min_quality_after", sm.min_quality_after);
    return sm;
  });
  r.verdicts = stage(r.report, hooks, "check", [&](Json& st) {
    SurfaceVerdicts v = surface_verdicts(r.dual);
    r.areas = surface_area_identity(r.primal, r.dual);
    st.set("invalid", v.invalid);
    st.set("fan_triangles", v.fan_triangles);
    st.set("area", area_json(r.areas));
    return v;
  });
  if (params.split && r.verdicts.invalid > 0) {
    r.split = stage(r.report, hooks, "split", [&](Json& st) {
      SplitParams sp;
      sp.max_rounds = params.split_rounds;
      const SurfaceSmoother smooth = [&](PolySurface& d) { smooth_surface(d, r.primal, params.smooth); };
      st = run_surface_split(r.primal, sp, smooth, r.dual, r.verdicts);
      r.areas = surface_area_identity(r.primal, r.dual);
      return st;
    });
  }
  if (params.require_valid && r.verdicts.invalid > 0) {
    std::string what = std::to_string(r.verdicts.invalid) + " polygons are not star-shaped (--require-valid):";
    for (const std::string& item : invalid_polygon_items(r, 10)) what += " " + item + ";";
    throw InputError(r.primal.source(), "", what);
  }
  return r;
}

std::vector<std::string> invalid_polygon_items(const SurfaceConvertResult& r, std::size_t limit) {
  std::vector<std::string> items;
  for (std::size_t i = 0; i < r.dual.num_polygons() && items.size() < limit; ++i)
    if (!r.verdicts.valid[i])
      items.push_back("polygon " + std::to_string(i) + " (vertex " + std::to_string(r.dual.primal_vertex(i) + 1) +
                      ", surface " + std::to_string(r.dual.surface(i)) + ")");
  return items;
}

Json write_surface_result(const SurfaceConvertResult& r, const std::string& path, const SurfaceWriter& writer,
                          const PolyWriteOptions& options) {
  std::vector<std::int32_t> valid(r.verdicts.valid.begin(), r.verdicts.valid.end());
  Json rec = Json::object();
  rec.set("path", path);
  rec.set("format", std::string(writer.name()));
  writer.write(r.dual, path, WriteContext{options, {CellField{"valid", std::move(valid)}}, {}}, rec);
  return rec;
}

SurfaceConvertResult convert_surface_file(TetSoup soup, const std::string& in, const std::string& out,
                                          std::string_view format, const SurfaceConvertParams& params,
                                          const PolyWriteOptions& options, const ConvertHooks& hooks) {
  const SurfaceWriter& writer = surface_writer_for(format, out);
  const std::string inputs[] = {in};
  check_output_target(inputs, out, OutputKind::File, options.foam.force, std::string(writer.extension()));
  SurfaceConvertResult r = convert_surface(soup, params, hooks);
  r.written = stage(r.report, hooks, "write", [&](Json& st) {
    Json w = write_surface_result(r, out, writer, options);
    st = w;
    return w;
  });
  return r;
}

Json surface_summary(const SurfaceConvertResult& r) {
  Json j = Json::object();
  j.set("input", r.primal.source());
  if (const Json* path = r.written.find("path")) j.set("output", *path);
  Json primal = Json::object();
  primal.set("cells", r.primal.num_cells());
  primal.set("vertices", r.primal.num_vertices());
  primal.set("edges", r.primal.num_edges());
  primal.set("surfaces", r.areas.surfaces.size());
  j.set("primal", std::move(primal));
  Json dual = Json::object();
  dual.set("polygons", r.dual.num_polygons());
  dual.set("points", r.dual.num_points());
  j.set("dual", std::move(dual));
  Json sm = Json::object();
  sm.set("sweeps", r.smooth.sweeps);
  sm.set("moved", r.smooth.moved);
  sm.set("min_quality_before", r.smooth.min_quality_before);
  sm.set("min_quality_after", r.smooth.min_quality_after);
  j.set("smooth", std::move(sm));
  j.set("invalid", r.verdicts.invalid);
  j.set("fan_triangles", r.verdicts.fan_triangles);
  if (r.split.find("rounds")) j.set("split", r.split);
  j.set("area", area_json(r.areas));
  Json stages = Json::array();
  for (const StageRecord& s : r.report.stages) {
    Json x = Json::object();
    x.set("name", s.name);
    x.set("seconds", s.seconds);
    stages.push(std::move(x));
  }
  j.set("stages", std::move(stages));
  j.set("seconds", r.report.seconds);
  return j;
}

}  // namespace polydual
