#include "mesh/validate.h"

#include <algorithm>
#include <set>
#include <unordered_map>

namespace polydual {

double cell_volume(const PolyMesh& pm, CellId c) {
  const auto pts = pm.cell_points(c);
  Vec3 R{};
  for (PointId p : pts) R += pm.points[p.idx];
  R = R / double(pts.size());
  double vol = 0;
  for (HalfFace h : pm.cell(c)) {
    const auto loop = pm.oriented_loop(h);
    Vec3 F{};
    for (PointId p : loop) F += pm.points[p.idx];
    F = F / double(loop.size());
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const Vec3 a = pm.points[loop[k].idx] - R, b = pm.points[loop[(k + 1) % loop.size()].idx] - R;
      vol += dot(a, cross(b, F - R)) / 6.0;
    }
  }
  return vol;
}

ValidationReport validate(const PolyMesh& pm, const ClassifiedTetMesh* primal) {
  ValidationReport r;
  r.cells = pm.num_cells();
  r.faces = pm.num_faces();
  r.points = pm.num_points();
  for (std::size_t f = 0; f < pm.num_faces(); ++f) {
    auto loop = pm.face(FaceId(f));
    std::vector<PointId> s(loop.begin(), loop.end());
    std::sort(s.begin(), s.end());
    bool bad = loop.size() < 3 || std::adjacent_find(s.begin(), s.end()) != s.end() ||
               !pm.face_owner[f].valid() || pm.face_owner[f].idx >= pm.num_cells() ||
               (pm.face_neighbour[f].valid() && pm.face_neighbour[f].idx >= pm.num_cells()) ||
               (pm.face_kind[f] == FaceKind::External) != !pm.face_neighbour[f].valid();
    r.face_errors += bad;
  }
  std::unordered_map<std::uint64_t, int> bal, uses;
  for (std::size_t c = 0; c < pm.num_cells(); ++c) {
    bal.clear();
    uses.clear();
    std::set<std::uint32_t> faces_seen;
    bool slit = false;
    for (HalfFace h : pm.cell(CellId(c))) {
      if (pm.half_face_cell(h) != CellId(c)) ++r.face_errors;
      if (!faces_seen.insert(h.face().idx).second) slit = true;
      const auto loop = pm.oriented_loop(h);
      for (std::size_t k = 0; k < loop.size(); ++k) {
        std::uint32_t a = loop[k].idx, b = loop[(k + 1) % loop.size()].idx;
        std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
        bal[key] += a < b ? 1 : -1;
        uses[key] += 1;
      }
    }
    bool closed = std::all_of(bal.begin(), bal.end(), [](auto& kv) { return kv.second == 0; });
    bool manifold = closed && std::all_of(uses.begin(), uses.end(), [](auto& kv) { return kv.second == 2; });
    r.closed_cells += closed;
    r.manifold_cells += manifold;
    r.slit_cells += slit;
    if (!closed && r.open_cells.size() < 100) r.open_cells.push_back(CellId(c));
    const double v = cell_volume(pm, CellId(c));
    if (closed && !slit && v <= 0) ++r.negative_volume_cells;
    r.material_volume[pm.cell_material[c]] += v;
  }
  if (primal) {
    std::set<std::pair<int, std::int32_t>> have;
    for (const ModelRef& m : pm.point_class)
      if (m.dim <= 1) have.insert({m.dim, m.tag});
    for (std::size_t f = 0; f < pm.num_faces(); ++f)
      if (pm.face_kind[f] != FaceKind::Interior) have.insert({2, pm.face_tag[f]});
    const char* names[3] = {"vertex", "edge", "face"};
    for (int dim = 0; dim < 3; ++dim)
      for (const ModelEntity& e : primal->model().entities[dim])
        if (!have.count({dim, e.tag}))
          r.missing_model_entities.push_back(std::string("model ") + names[dim] + " " + std::to_string(e.tag));
  }
  return r;
}

Json ValidationReport::to_json() const {
  Json j = Json::object();
  j.set("cells", cells);
  j.set("faces", faces);
  j.set("points", points);
  j.set("closed_cells", closed_cells);
  j.set("manifold_cells", manifold_cells);
  j.set("slit_cells", slit_cells);
  j.set("face_errors", face_errors);
  j.set("negative_volume_cells", negative_volume_cells);
  Json mv = Json::array();
  for (auto& [tag, v] : material_volume) {
    Json o = Json::object();
    o.set("tag", tag);
    o.set("volume", v);
    mv.push(o);
  }
  j.set("material_volumes", mv);
  Json miss = Json::array();
  for (auto& s : missing_model_entities) miss.push(s);
  j.set("missing_model_entities", miss);
  j.set("ok", ok());
  return j;
}

}  // namespace polydual
