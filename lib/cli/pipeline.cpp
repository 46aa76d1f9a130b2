#include "cli/pipeline.h"

#include <map>

#include "core/error.h"
#include "io/foam_writer.h"
#include "io/read_tet_mesh.h"
#include "io/vtu_poly_writer.h"
#include "mesh/validate.h"

namespace polydual::cli {

// At most this many invalid cells are listed one by one in a summary.
constexpr std::size_t kWhereLimit = 200;

ClassifiedTetMesh load_classified(const std::string& path, const ClassifyParams& params, Json& seconds) {
  Timer t;
  TetSoup soup = read_tet_mesh(path);
  seconds.set("read", t.seconds());
  Timer t2;
  ClassifiedTetMesh m = classify(soup, params);
  seconds.set("classify", t2.seconds());
  return m;
}

Json model_summary(const ClassifiedTetMesh& m) {
  Json model = Json::object();
  model.set("vertices", m.model().count(0));
  model.set("edges", m.model().count(1));
  model.set("faces", m.model().count(2));
  model.set("regions", m.model().count(3));
  Json faces = Json::array();
  for (const ModelEntity& f : m.model().entities[2]) {
    Json o = Json::object();
    o.set("tag", f.tag);
    const char* kind = f.regions.size() < 2 ? "external" : (f.regions[0] == f.regions[1] ? "fracture" : "interface");
    o.set("kind", kind);
    Json r = Json::array();
    for (auto x : f.bounds) r.push(x);
    o.set("regions", r);
    faces.push(o);
  }
  model.set("face_list", faces);
  return model;
}

Json poly_summary(const PolyMesh& pm, const std::vector<CellVerdict>& verdicts, const ClassifiedTetMesh* primal) {
  ValidationReport rep = validate(pm, primal);
  Json j = Json::object();
  j.set("cells", pm.num_cells());
  j.set("faces", pm.num_faces());
  j.set("points", pm.num_points());
  std::size_t invalid = 0;
  for (const auto& v : verdicts) invalid += !v.valid;
  j.set("invalid_cells", invalid);
  if (primal) {
    // Where the invalid cells sit: the classification of their primal vertex
    // (paper §4: only at concave edges/corners and fracture tips).
    const char* names[4] = {"model_vertex", "model_edge", "model_face", "interior"};
    std::size_t by_dim[4] = {0, 0, 0, 0};
    Json where = Json::array();
    std::size_t listed = 0;
    // cell_primal is in the input's numbering: map it back to the mesh's ids.
    std::vector<std::uint32_t> mesh_id;
    for (std::size_t v = 0; v < primal->num_vertices(); ++v) {
      const std::uint32_t in = primal->input_vertex(VertexId(v));
      if (in >= mesh_id.size()) mesh_id.resize(in + 1, VertexId::kInvalid);
      mesh_id[in] = std::uint32_t(v);
    }
    for (std::size_t c = 0; c < verdicts.size(); ++c) {
      if (verdicts[c].valid) continue;
      const std::uint32_t in = pm.cell_primal[c].idx;
      if (in >= mesh_id.size() || mesh_id[in] == VertexId::kInvalid)
        throw InputError(primal->source(), "cell " + std::to_string(c + 1),
                         "the dual cell's primal vertex " + std::to_string(in + 1) + " is not in this tet mesh");
      const VertexId v(mesh_id[in]);
      const ModelRef cls = primal->vertex_class(v);
      ++by_dim[cls.dim];
      if (listed++ < kWhereLimit) {
        Json o = Json::object();
        o.set("cell", c);
        o.set("primal_vertex", in);
        o.set("class", names[cls.dim]);
        o.set("tag", cls.tag);
        const Point3& p = primal->point(v);
        Json xyz = Json::array();
        xyz.push(p.x);
        xyz.push(p.y);
        xyz.push(p.z);
        o.set("xyz", xyz);
        o.set("bad_tets", verdicts[c].bad_tets);
        where.push(o);
      }
    }
    Json by = Json::object();
    for (int d = 0; d < 4; ++d) by.set(names[d], by_dim[d]);
    j.set("invalid_by_class", by);
    j.set("invalid_where", where);
  }
  j.set("closed_cells", rep.closed_cells);
  j.set("slit_cells", rep.slit_cells);
  j.set("face_errors", rep.face_errors);
  j.set("negative_volume_cells", rep.negative_volume_cells);
  // Per material: cells, dual volume (decomposition, double), primal volume.
  std::map<std::int32_t, std::size_t> cells;
  std::map<std::int32_t, double> primal_vol;
  for (auto m : pm.cell_material) ++cells[m];
  if (primal)
    for (std::size_t t = 0; t < primal->num_tets(); ++t) primal_vol[primal->region(TetId(t))] += primal->tet_volume(TetId(t));
  Json mats = Json::array();
  for (auto& [tag, n] : cells) {
    Json o = Json::object();
    o.set("tag", tag);
    o.set("cells", n);
    o.set("volume", rep.material_volume[tag]);
    if (primal) o.set("primal_volume", primal_vol[tag]);
    mats.push(o);
  }
  j.set("materials", mats);
  Json miss = Json::array();
  for (auto& s : rep.missing_model_entities) miss.push(s);
  j.set("missing_model_entities", miss);
  j.set("topology_ok", rep.ok());
  return j;
}

std::string output_format(const std::string& requested, const std::string& out) {
  if (!requested.empty()) {
    if (requested != "vtu" && requested != "foam")
      throw UsageError("--format must be vtu or foam, not '" + requested + "'");
    return requested;
  }
  if (out.size() >= 4 && out.compare(out.size() - 4, 4, ".vtu") == 0) return "vtu";
  return out.find('.') == std::string::npos || out.back() == '/' ? "foam" : "vtu";
}

Json write_poly(const PolyMesh& pm, const std::vector<CellVerdict>& verdicts, const std::string& out,
                const std::string& format) {
  Json rec = Json::object();
  rec.set("path", out);
  rec.set("format", format);
  if (format == "foam") {
    FoamReport r = write_foam(pm, out);
    rec.set("foam", r.to_json());
  } else {
    std::vector<std::int32_t> valid(pm.num_cells()), bad(pm.num_cells());
    for (std::size_t c = 0; c < verdicts.size(); ++c) {
      valid[c] = verdicts[c].valid;
      bad[c] = verdicts[c].bad_tets;
    }
    write_vtu_poly(pm, out, {CellField{"valid", valid}, CellField{"bad_tets", bad}}, VtuOptions{true});
  }
  return rec;
}

}  // namespace polydual::cli
