#include "pipeline/summary.h"

#include <map>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "quality/flatness.h"
#include "quality/metrics.h"
#include "quality/model_wedge.h"

namespace polydual {

namespace {

// At most this many invalid cells are listed one by one in a summary (the
// counts by class cover them all).
constexpr std::size_t kWhereLimit = 200;
constexpr const char* kClassNames[4] = {"model_vertex", "model_edge", "model_face", "interior"};

const char* face_kind_name(const ModelEntity& f) {
  switch (face_kind(f)) {
    case FaceKind::External: return "external";
    case FaceKind::Interface: return "interface";
    case FaceKind::Fracture: return "fracture";
    case FaceKind::Interior: break;
  }
  return "interior";
}

Json xyz_json(const Point3& p) {
  Json a = Json::array();
  a.push(p.x);
  a.push(p.y);
  a.push(p.z);
  return a;
}

// Mesh vertex id of each input vertex number (cells name their primal vertex
// in the input's numbering).
std::vector<std::uint32_t> mesh_ids_of_inputs(const ClassifiedTetMesh& primal) {
  std::vector<std::uint32_t> id;
  for (std::size_t v = 0; v < primal.num_vertices(); ++v) {
    const std::uint32_t in = primal.input_vertex(VertexId(v));
    if (in >= id.size()) id.resize(in + 1, VertexId::kInvalid);
    id[in] = std::uint32_t(v);
  }
  return id;
}

// Where the invalid cells sit: the classification of their primal vertex
// (paper §4: only at concave edges/corners and fracture tips).
void add_invalid_where(Json& j, const PolyMesh& pm, const CheckResult& check, const ClassifiedTetMesh& primal) {
  const std::vector<std::uint32_t> mesh_id = mesh_ids_of_inputs(primal);
  std::size_t by_dim[4] = {0, 0, 0, 0};
  Json where = Json::array();
  std::size_t listed = 0;
  for (std::size_t c = 0; c < check.verdicts.size(); ++c) {
    if (check.verdicts[c].valid) continue;
    const std::uint32_t in = pm.cell_primal[c].idx;
    if (in >= mesh_id.size() || mesh_id[in] == VertexId::kInvalid)
      throw InputError(primal.source(), "cell " + std::to_string(c + 1),
                       "the dual cell's primal vertex " + std::to_string(in + 1) + " is not in this tet mesh");
    const VertexId v(mesh_id[in]);
    const ModelRef cls = primal.vertex_class(v);
    ++by_dim[cls.dim];
    if (listed++ >= kWhereLimit) continue;
    Json o = Json::object();
    o.set("cell", c);
    o.set("primal_vertex", in);
    o.set("class", kClassNames[cls.dim]);
    o.set("tag", cls.tag);
    o.set("xyz", xyz_json(primal.point(v)));
    o.set("bad_tets", check.verdicts[c].bad_tets);
    where.push(o);
  }
  Json by = Json::object();
  for (int d = 0; d < 4; ++d) by.set(kClassNames[d], by_dim[d]);
  j.set("invalid_by_class", by);
  j.set("invalid_where", where);
}

// Per material: cells, dual volume (decomposition, double), primal volume.
Json materials_json(const PolyMesh& pm, const ValidationReport& rep, const ClassifiedTetMesh* primal) {
  std::map<std::int32_t, std::size_t> cells;
  std::map<std::int32_t, double> primal_vol;
  for (auto m : pm.cell_material) ++cells[m];
  if (primal)
    for (std::size_t t = 0; t < primal->num_tets(); ++t)
      primal_vol[primal->region(TetId(t))] += primal->tet_volume(TetId(t));
  Json mats = Json::array();
  for (auto& [tag, n] : cells) {
    Json o = Json::object();
    o.set("tag", tag);
    o.set("cells", n);
    auto v = rep.material_volume.find(tag);
    o.set("volume", v == rep.material_volume.end() ? 0.0 : v->second);
    if (primal) o.set("primal_volume", primal_vol[tag]);
    else if (const auto p = rep.primal_material_volume.find(tag); p != rep.primal_material_volume.end())
      o.set("primal_volume", p->second);  // a mixed primal's (pipeline/convert_mixed.h)
    mats.push(o);
  }
  return mats;
}

// The dual's record: the draft's stats with the cleanup's counts.
Json dual_summary(const ConvertReport& report) {
  const StageRecord* dual = report.stage("dual");
  const StageRecord* cleanup = report.stage("cleanup");
  if (!dual) return Json();
  Json j = dual->stats;
  if (cleanup)
    for (const char* k : {"merged_points", "collapsed_points", "dropped_faces"})
      if (const Json* v = cleanup->stats.find(k)) j.set(k, *v);
  if (Json* sec = j.find("seconds"))
    for (const char* part : {"cleanup", "cells"})
      if (const StageRecord* p = report.stage(part)) sec->set(part, p->seconds);
  return j;
}

// Seconds per stage; "dual" is the whole of Algorithm 1 (draft, cleanup,
// cells), "star_test" the first check, as the summaries always reported.
Json seconds_summary(const ConvertReport& report) {
  Json seconds = Json::object();
  for (const StageRecord& s : report.stages) {
    if (s.name == "cleanup" || s.name == "cells") continue;
    double t = s.seconds;
    if (s.name == "dual")
      for (const char* part : {"cleanup", "cells"})
        if (const StageRecord* p = report.stage(part)) t += p->seconds;
    seconds.set(s.name == "check" ? "star_test" : s.name, t);
  }
  seconds.set("total", report.seconds);
  Json stages = Json::object();
  for (const StageRecord& s : report.stages) stages.set(s.name, s.seconds);
  seconds.set("stages", stages);
  return seconds;
}

// The process's peak resident memory (MB) when each stage ended: where a
// run's memory peak is reached.
Json peak_memory_summary(const ConvertReport& report) {
  Json j = Json::object();
  for (const StageRecord& s : report.stages) j.set(s.name, s.peak_rss_mb);
  return j;
}

// The cells above OptimReport::kWorstBound at the end (worst first, at most
// kMaxWorstCells), each with the model's shape at its primal vertex as its
// material's tets see it (quality/model_wedge.h): a small wedge or solid
// angle says the model leaves the cell no room; a cell without one is the
// optimiser's to improve. Null for a mesh with no primal vertices.
Json worst_cells_summary(const ConvertResult& r, Metric metric) {
  const PolyMesh& pm = r.mesh;
  if (pm.num_cells() == 0 || pm.cell_primal.size() != pm.num_cells()) return Json();
  const std::vector<double> q = cell_qualities(build_stencil(pm), metric, pm.points);
  std::vector<std::pair<double, std::uint32_t>> above;
  for (std::uint32_t c = 0; c < q.size(); ++c)
    if (!(q[c] <= OptimReport::kWorstBound)) above.push_back({q[c], c});
  std::sort(above.begin(), above.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  });
  Json j = Json::object();
  // The mesh returned: its worst and mean cell (the optimiser's records are
  // of the meshes it left, before any later stage moved points).
  double sum = 0, worst = 0;
  for (double x : q) {
    sum += x;
    worst = std::max(worst, x);
  }
  j.set("max", std::isfinite(worst) ? Json(worst) : Json());
  j.set("mean", std::isfinite(sum) ? Json(sum / double(q.size())) : Json());
  j.set("bound", OptimReport::kWorstBound);
  j.set("cells_above", above.size());
  if (above.size() > OptimReport::kMaxWorstCells) above.resize(OptimReport::kMaxWorstCells);
  const std::vector<VertexId> internal = internal_of_input(r.primal);
  Json cells = Json::array();
  for (const auto& [quality, c] : above) {
    Json w = Json::object();
    w.set("cell", c);
    w.set("quality", std::isfinite(quality) ? Json(quality) : Json());
    const VertexId in = pm.cell_primal[c];
    w.set("primal_vertex", in.idx);
    if (in.idx < internal.size() && internal[in.idx].valid()) {
      const VertexId v = internal[in.idx];
      const ModelRef cls = r.primal.vertex_class(v);
      const VertexWedge wedge = vertex_wedge(r.primal, v, pm.cell_material[c]);
      w.set("class", kClassNames[cls.dim]);
      w.set("tag", cls.tag);
      w.set("solid_angle_sr", wedge.solid_angle_sr);
      w.set("min_wedge_deg", wedge.min_wedge_deg);
      w.set("wedge_model_edge", wedge.wedge_edge.dim == 1 ? Json(wedge.wedge_edge.tag) : Json());
    }
    cells.push(std::move(w));
  }
  j.set("cells", std::move(cells));
  return j;
}

}  // namespace

Json ignored_summary(const IgnoredEntities& ignored) {
  Json j = Json::object();
  j.set("points", ignored.points);
  j.set("curves", ignored.curves);
  j.set("surfaces", ignored.surfaces);
  j.set("elements", ignored.elements);
  j.set("chains", ignored.chains);
  return j;
}

Json model_summary(const ClassifiedTetMesh& m) {
  Json model = Json::object();
  for (int d = 0; d < 4; ++d) model.set(d == 0 ? "vertices" : d == 1 ? "edges" : d == 2 ? "faces" : "regions",
                                        m.model().count(d));
  Json faces = Json::array();
  for (const ModelEntity& f : m.model().entities[2]) {
    Json o = Json::object();
    o.set("tag", f.tag);
    o.set("kind", face_kind_name(f));
    // The file's marker (group) when the face was split from it or renamed, and its name.
    if (f.source_tag && *f.source_tag != f.tag) o.set("source_tag", *f.source_tag);
    if (!f.name.empty()) o.set("name", f.name);
    Json r = Json::array();
    for (auto x : f.bounds) r.push(x);
    o.set("regions", r);
    faces.push(o);
  }
  model.set("face_list", faces);
  // Per face marker of the file: what the feature inference split and why.
  Json markers = Json::array();
  for (const MarkerFeatures& mf : m.marker_features()) {
    Json o = Json::object();
    if (mf.marker) o.set("marker", *mf.marker);
    else o.set("marker", Json());
    o.set("facets", mf.facets);
    o.set("model_faces", mf.model_faces);
    o.set("model_edges", mf.model_edges);
    o.set("corners", mf.corners);
    o.set("sharp_edges", mf.sharp_edges);
    o.set("feature_edges_strong", mf.strong_edges);
    o.set("feature_edges_chain", mf.chain_edges);
    o.set("noise_edges", mf.noise_edges);
    markers.push(o);
  }
  model.set("markers", markers);
  return model;
}

Json mesh_summary(const PolyMesh& pm, const CheckResult& check, const ClassifiedTetMesh* primal,
                  const FlatnessStats* flatness) {
  const ValidationReport& rep = check.validation;
  Json j = Json::object();
  j.set("cells", pm.num_cells());
  j.set("faces", pm.num_faces());
  j.set("points", pm.num_points());
  j.set("invalid_cells", check.invalid_cells);
  if (primal) add_invalid_where(j, pm, check, *primal);
  j.set("closed_cells", rep.closed_cells);
  j.set("slit_cells", rep.slit_cells);
  j.set("face_errors", rep.face_errors);
  j.set("negative_volume_cells", rep.negative_volume_cells);
  j.set("materials", materials_json(pm, rep, primal));
  Json miss = Json::array();
  for (auto& s : rep.missing_model_entities) miss.push(s);
  j.set("missing_model_entities", miss);
  j.set("topology_ok", rep.ok());
  // Materials bounded by planar model faces: the dual's volume against the
  // primal's (design §10; double sums within a relative tolerance).
  j.set("geometry_ok", rep.geometry_ok());
  j.set("volume_mismatches", volume_mismatches_json(rep.volume_mismatches));
  // Each failed check with its cells (empty: topology and geometry ok).
  j.set("defects", defects_json(rep.defects()));
  j.set("face_flatness", (flatness ? *flatness : flatness_stats(pm)).to_json());
  return j;
}

Json convert_summary(const ConvertResult& r, const PipelineParams& params) {
  Json j = Json::object();
  if (const StageRecord* read = r.report.stage("read")) {
    j.set("input", *read->stats.find("path"));
  }
  if (r.written.find("path")) j.set("output", r.written);
  if (r.mixed) {
    // A mixed input (design §14): its cells per type; "tets" counts its tets.
    j.set("mixed", true);
    j.set("input_cells", describe_cell_counts(r.mixed->cell_counts));
    Json by_type = Json::object();
    for (int t = 0; t < kNumCellTypes; ++t)
      if (r.mixed->cell_counts[t]) by_type.set(std::string(descriptor(CellType(t)).plural), r.mixed->cell_counts[t]);
    j.set("cells_by_type", by_type);
    j.set("tets", r.mixed->cell_counts[std::size_t(CellType::Tet)]);
    j.set("vertices", r.mixed->mesh.num_vertices());
  } else {
    j.set("tets", r.input_tets ? r.input_tets : r.primal.num_tets());
    j.set("vertices", r.primal.num_vertices());
  }
  j.set("ignored", ignored_summary(r.ignored));
  Json warnings = Json::array();
  for (const std::string& w : r.warnings) warnings.push(w);
  j.set("warnings", warnings);
  if (!r.mixed) j.set("model", model_summary(r.primal));
  Json mesh = mesh_summary(r.mesh, r.check, r.mixed ? nullptr : &r.primal, r.flatness ? &*r.flatness : nullptr);
  for (const char* k : {"cells", "faces", "points", "invalid_cells", "closed_cells", "slit_cells", "face_errors",
                        "negative_volume_cells", "materials", "missing_model_entities", "topology_ok",
                        "geometry_ok", "volume_mismatches", "defects", "invalid_by_class", "invalid_where", "face_flatness"})
    if (const Json* v = mesh.find(k)) j.set(k, *v);
  j.set("invalid_before", r.report.invalid_before);
  j.set("invalid_after", r.report.invalid_after);
  const StageRecord* first_check = r.report.stage("check");
  Json star = Json::object();
  if (first_check) {
    star.set("decomposition_tets", *first_check->stats.find("decomposition_tets"));
    star.set("exact_fallbacks", *first_check->stats.find("exact_fallbacks"));
  }
  j.set("star_test", star);
  j.set("dual", dual_summary(r.report));
  const StageRecord* opt = r.report.stage("optimize");
  j.set("optimize", opt ? opt->stats : Json());
  // The split loop (split/split.h): cells split by cause, rounds; null with --no-split.
  const StageRecord* split = r.report.stage("split");
  j.set("split", split ? split->stats : Json());
  if (const StageRecord* tet = r.report.stage("optimize_tets")) j.set("optimize_tets", tet->stats);
  // OpenFOAM's verdict (face pyramids, face tets) on the mesh written.
  if (const StageRecord* of = r.report.stage("openfoam_check")) j.set("openfoam", of->stats);
  j.set("worst_cells", worst_cells_summary(r, params.optim.metric));
  j.set("params", params.to_json());
  j.set("seconds", seconds_summary(r.report));
  j.set("peak_rss_mb", peak_memory_summary(r.report));
  return j;
}

}  // namespace polydual
