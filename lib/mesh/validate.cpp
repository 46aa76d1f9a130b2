#include "mesh/validate.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <set>
#include <span>
#include <tuple>
#include <utility>


namespace polydual {

namespace {

// The volume of cell c by its decomposition tets (a, b, F, R) around the mean
// R of `pts` (the cell's distinct points in cell_points order); F and each
// edge follow the cell's outward loops. No allocation.
double volume_around(const PolyMesh& pm, CellId c, std::span<const PointId> pts) {
  Vec3 R{};
  for (PointId p : pts) R += pm.points[p.idx];
  R = R / double(pts.size());
  double vol = 0;
  for (HalfFace h : pm.cell(c)) {
    const auto f = pm.face(h.face());
    const std::size_t n = f.size();
    // The oriented loop: side 1 sees the stored loop reversed.
    auto at = [&](std::size_t k) { return pm.points[(h.side() == 0 ? f[k] : f[n - 1 - k]).idx]; };
    Vec3 F{};
    for (std::size_t k = 0; k < n; ++k) F += at(k);
    F = F / double(n);
    for (std::size_t k = 0; k < n; ++k) {
      const Vec3 a = at(k) - R, b = at((k + 1) % n) - R;
      vol += dot(a, cross(b, F - R)) / 6.0;
    }
  }
  return vol;
}

}  // namespace

double cell_volume(const PolyMesh& pm, CellId c) {
  const std::vector<PointId> pts = pm.cell_points(c);  // one cell: no scan's stamps
  return volume_around(pm, c, pts);
}

namespace {

// Whether loop has a point twice (a short loop by pairs, a long one sorted).
bool has_repeated_point(std::span<const PointId> loop, std::vector<PointId>& sorted) {
  if (loop.size() <= 16) {
    for (std::size_t i = 1; i < loop.size(); ++i)
      for (std::size_t j = 0; j < i; ++j)
        if (loop[i] == loop[j]) return true;
    return false;
  }
  sorted.assign(loop.begin(), loop.end());
  std::sort(sorted.begin(), sorted.end());
  return std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end();
}

// Per face, what check_faces and check_half_face_references found.
constexpr char kLoopInRange = 1;  // every point id of its loop in range
constexpr char kFaceError = 2;    // counted in face_errors

// Per face: its loop, owner, neighbour and kind on their own (in parallel;
// the error count is a sum of integers). Returns each face's status (the
// later phases read only the loops in range).
std::vector<char> check_faces(const PolyMesh& pm, ValidationReport& r) {
  const std::size_t nf = pm.num_faces();
  std::vector<char> status(nf, 0);
  tbb::enumerable_thread_specific<std::pair<std::size_t, std::vector<PointId>>> local;  // (errors, scratch)
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nf, 4096), [&](const auto& range) {
    auto& [errors, sorted] = local.local();
    for (std::size_t f = range.begin(); f != range.end(); ++f) {
      const auto loop = pm.face(FaceId(f));
      bool in_range = true;
      for (PointId p : loop) in_range = in_range && p.idx < pm.num_points();
      const CellId own = pm.face_owner[f], nb = pm.face_neighbour[f];
      const bool bad = loop.size() < 3 || !in_range || has_repeated_point(loop, sorted) || !own.valid() ||
                       own.idx >= pm.num_cells() || (nb.valid() && nb.idx >= pm.num_cells()) ||
                       (pm.face_kind[f] == FaceKind::External) != !nb.valid();
      status[f] = char((in_range ? kLoopInRange : 0) | (bad ? kFaceError : 0));
      errors += bad;
    }
  });
  for (const auto& [errors, sorted] : local) r.face_errors += errors;
  return status;
}

// Every half-face listed by the cell it belongs to, exactly once; none listed
// for a face without a neighbour. A reference to no face or from the wrong
// cell is an error of its own (its cell listed in error_cells); a face whose
// half-faces are listed wrongly is marked kFaceError.
void check_half_face_references(const PolyMesh& pm, ValidationReport& r, std::vector<char>& status) {
  std::vector<std::uint8_t> refs(2 * pm.num_faces(), 0);
  std::size_t last_error_cell = pm.num_cells();
  for (std::size_t c = 0; c < pm.num_cells(); ++c)
    for (HalfFace h : pm.cell(CellId(c))) {
      if (h.face().idx >= pm.num_faces() || pm.half_face_cell(h) != CellId(c)) {
        ++r.face_errors;
        if (last_error_cell != c) {
          ++r.error_cell_count;
          if (r.error_cells.size() < kListedDefects) r.error_cells.push_back(CellId(c));
        }
        last_error_cell = c;
        continue;
      }
      refs[h.code] = std::uint8_t(std::min(refs[h.code] + 1, 2));
    }
  for (std::size_t f = 0; f < pm.num_faces(); ++f) {
    const int expect_neighbour = pm.face_neighbour[f].valid() ? 1 : 0;
    const bool bad = refs[2 * f] != 1 || refs[2 * f + 1] != expect_neighbour;
    r.face_errors += bad;
    if (bad) status[f] |= kFaceError;
  }
}

// The faces marked kFaceError: their number and the first kListedDefects.
void list_error_faces(const std::vector<char>& status, ValidationReport& r) {
  for (std::size_t f = 0; f < status.size(); ++f) {
    if (!(status[f] & kFaceError)) continue;
    ++r.error_face_count;
    if (r.error_faces.size() < kListedDefects) r.error_faces.push_back(FaceId(f));
  }
}

// Closure, orientation, slits and volume of every cell. An edge (a, b) of a
// half-face loop counts forward when a < b: a closed cell uses each edge as
// often forward as backward; a reversed face makes some edge's two uses point
// the same way.
// What check_cells finds in one cell.
struct CellCheck {
  bool sound = true;  // every half-face names a face whose points exist
  bool closed = true, manifold = true, misoriented = false, slit = false;
  double volume = 0;  // when sound
};

// Per-thread scratch of check_cell: the cell's distinct points (stamps) and,
// for a small cell, each point's index among them; the directed edge counts
// of a small cell by those indices (kSmall x kSmall, zero between cells) and
// the entries used; the edge keys (min << 32 | max) used forward (min to max)
// and backward for a larger or unsound cell; the faces seen.
struct CellScratch {
  static constexpr std::size_t kSmall = 64;
  explicit CellScratch(const PolyMesh& pm) : points(pm), local(pm.num_points(), 0) {}
  CellPointScan points;
  std::vector<std::uint8_t> local;
  std::vector<std::uint32_t> count = std::vector<std::uint32_t>(kSmall * kSmall, 0);
  std::vector<std::uint16_t> used;
  std::vector<std::uint64_t> forward, backward;
  std::vector<std::uint32_t> faces_seen;
};

// Per edge key of the sorted forward and backward lists, its count in each:
// closed when equal, manifold when they add up to 2, misoriented when they
// differ by 2 or more.
void add_edge_counts(std::size_t nf, std::size_t nb, CellCheck& r) {
  r.closed &= nf == nb;
  r.manifold &= nf + nb == 2;
  r.misoriented |= nf >= nb + 2 || nb >= nf + 2;
}

void count_edge_uses(const std::vector<std::uint64_t>& fw, const std::vector<std::uint64_t>& bw, CellCheck& r) {
  std::size_t i = 0, j = 0;
  while (i < fw.size() || j < bw.size()) {
    const std::uint64_t key = j == bw.size() || (i < fw.size() && fw[i] < bw[j]) ? fw[i] : bw[j];
    std::size_t nf = 0, nb = 0;
    for (; i < fw.size() && fw[i] == key; ++i) ++nf;
    for (; j < bw.size() && bw[j] == key; ++j) ++nb;
    add_edge_counts(nf, nb, r);
  }
}

// Calls fn(a, b) for every edge of cell c's oriented loops (mesh point ids),
// skipping the loops not in range.
template <class Fn>
void for_each_loop_edge(const PolyMesh& pm, std::uint32_t c, const std::vector<char>& status, Fn&& fn) {
  for (HalfFace h : pm.cell(CellId(c))) {
    if (h.face().idx >= pm.num_faces() || !(status[h.face().idx] & kLoopInRange)) continue;
    const auto f = pm.face(h.face());
    const std::size_t n = f.size();
    auto at = [&](std::size_t k) { return (h.side() == 0 ? f[k] : f[n - 1 - k]).idx; };
    for (std::size_t k = 0; k < n; ++k) fn(at(k), at((k + 1) % n));
  }
}

// The edge uses of a sound cell of at most kSmall points, counted by local
// index pairs (no sort): the same counts per unordered edge as the sorted
// key lists (nf, nb are the two directions' counts, and every test is
// symmetric in them). A loop edge from a point to itself counts backward
// only, as in the sorted lists.
void count_small_cell_edges(const PolyMesh& pm, std::uint32_t c, const std::vector<char>& status,
                            std::span<const PointId> points, CellScratch& s, CellCheck& r) {
  constexpr std::size_t K = CellScratch::kSmall;
  for (std::size_t i = 0; i < points.size(); ++i) s.local[points[i].idx] = std::uint8_t(i);
  s.used.clear();
  for_each_loop_edge(pm, c, status, [&](std::uint32_t a, std::uint32_t b) {
    const std::uint16_t i = std::uint16_t(s.local[a] * K + s.local[b]);
    if (s.count[i]++ == 0) s.used.push_back(i);
  });
  for (std::uint16_t i : s.used) {
    const std::size_t a = i / K, b = i % K;
    if (a == b) add_edge_counts(0, s.count[i], r);
    else add_edge_counts(s.count[i], s.count[b * K + a], r);
  }
  for (std::uint16_t i : s.used) s.count[i] = 0;
}

// The edge uses of any cell by sorted key lists (loops out of range skipped).
void count_cell_edges_sorted(const PolyMesh& pm, std::uint32_t c, const std::vector<char>& status,
                             CellScratch& s, CellCheck& r) {
  s.forward.clear();
  s.backward.clear();
  for_each_loop_edge(pm, c, status, [&](std::uint32_t a, std::uint32_t b) {
    (a < b ? s.forward : s.backward).push_back((std::uint64_t(std::min(a, b)) << 32) | std::max(a, b));
  });
  std::sort(s.forward.begin(), s.forward.end());
  std::sort(s.backward.begin(), s.backward.end());
  count_edge_uses(s.forward, s.backward, r);
}

// Closed: every edge of the cell's oriented loops is used once in each
// direction; manifold: by exactly two loops; slit: a face appears twice.
CellCheck check_cell(const PolyMesh& pm, std::uint32_t c, const std::vector<char>& status, CellScratch& s) {
  CellCheck r;
  s.faces_seen.clear();
  for (HalfFace h : pm.cell(CellId(c))) {
    if (h.face().idx >= pm.num_faces() || !(status[h.face().idx] & kLoopInRange)) {
      r.sound = false;
      continue;
    }
    s.faces_seen.push_back(h.face().idx);
  }
  std::sort(s.faces_seen.begin(), s.faces_seen.end());
  r.slit = std::adjacent_find(s.faces_seen.begin(), s.faces_seen.end()) != s.faces_seen.end();
  if (!r.sound) {
    count_cell_edges_sorted(pm, c, status, s, r);
    return r;
  }
  const std::span<const PointId> points = s.points(CellId(c));  // cell_points order
  if (points.size() <= CellScratch::kSmall) count_small_cell_edges(pm, c, status, points, s, r);
  else count_cell_edges_sorted(pm, c, status, s, r);
  r.volume = volume_around(pm, CellId(c), points);
  return r;
}

// Every cell checked in parallel, then counted and summed in cell order (the
// volumes' sums do not depend on the thread count).
void check_cells(const PolyMesh& pm, const std::vector<char>& status, ValidationReport& r) {
  const std::size_t nc = pm.num_cells();
  std::vector<CellCheck> checks(nc);
  tbb::enumerable_thread_specific<CellScratch> scratch(std::cref(pm));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nc, 256), [&](const auto& range) {
    CellScratch& s = scratch.local();
    for (std::size_t c = range.begin(); c != range.end(); ++c)
      checks[c] = check_cell(pm, static_cast<std::uint32_t>(c), status, s);
  });
  for (std::size_t c = 0; c < nc; ++c) {
    const CellCheck& k = checks[c];
    r.closed_cells += k.closed;
    r.manifold_cells += k.closed && k.manifold;
    r.misoriented_cells += k.misoriented;
    r.slit_cells += k.slit;
    if (!k.closed && r.open_cells.size() < kListedDefects) r.open_cells.push_back(CellId(c));
    if (k.misoriented && r.misoriented_list.size() < kListedDefects) r.misoriented_list.push_back(CellId(c));
    if (!k.sound) continue;
    if (k.closed && !k.slit && k.volume <= 0) ++r.negative_volume_cells;
    r.material_volume[pm.cell_material[c]] += k.volume;
  }
}

// design §10: every model vertex is a dual point (at its place), every model edge
// is covered by dual edges, every model face by dual faces with its tag.
void check_model_entities(const PolyMesh& pm, const std::vector<char>& status, const PrimalReference& primal,
                          ValidationReport& r) {
  std::set<std::pair<int, std::int32_t>> have;
  for (std::size_t p = 0; p < pm.num_points(); ++p)
    if (const ModelRef c = pm.point_class[p];
        c.dim == 0 && primal.model_vertices.count({c.tag, pm.points[p].x, pm.points[p].y, pm.points[p].z}))
      have.insert({0, c.tag});
  // A dual edge lies on model edge e when one end is on e and the other on e
  // or on a model vertex that bounds e.
  auto along = [&](ModelRef on_edge, ModelRef other) {
    return other == on_edge || (other.dim == 0 && primal.edge_vertex.count({on_edge.tag, other.tag}));
  };
  for (std::size_t f = 0; f < pm.num_faces(); ++f) {
    if (!(status[f] & kLoopInRange)) continue;
    const auto loop = pm.face(FaceId(f));
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const ModelRef a = pm.point_class[loop[k].idx], b = pm.point_class[loop[(k + 1) % loop.size()].idx];
      if (a.dim == 1 && along(a, b)) have.insert({1, a.tag});
      if (b.dim == 1 && along(b, a)) have.insert({1, b.tag});
    }
    if (pm.face_kind[f] != FaceKind::Interior) have.insert({2, pm.face_tag[f]});
  }
  const char* names[3] = {"vertex", "edge", "face"};
  for (int dim = 0; dim < 3; ++dim)
    for (std::int32_t tag : primal.entities[dim])
      if (!have.count({dim, tag}))
        r.missing_model_entities.push_back(std::string("model ") + names[dim] + " " + std::to_string(tag));
}

// Regions bounded by a model face (external or interface; a fracture has the
// same region on both sides and its dual faces cancel within it) that is not
// planar (ModelEntity::planar, decided exactly by classify()).
std::set<std::int32_t> regions_with_curved_faces(const ClassifiedTetMesh& primal) {
  std::set<std::int32_t> curved;
  for (const ModelEntity& f : primal.model().entities[2])
    if (!f.planar) curved.insert(f.tag);
  std::set<std::int32_t> regions;
  for (std::int32_t tag : curved) {
    const ModelEntity* f = primal.model().find(2, tag);
    if (!f || (f->regions.size() == 2 && f->regions[0] == f->regions[1])) continue;
    regions.insert(f->regions.begin(), f->regions.end());
  }
  return regions;
}

// Per-material dual volume against the primal's (double sums, relative tolerance).
void check_volumes(const PrimalReference& primal, double tol, ValidationReport& r) {
  r.volume_rel_tol = tol;
  r.primal_material_volume = primal.material_volume;
  std::set<std::int32_t> materials;
  for (const auto& [tag, v] : r.primal_material_volume) materials.insert(tag);
  for (const auto& [tag, v] : r.material_volume) materials.insert(tag);
  for (std::int32_t tag : materials) {
    if (primal.curved_regions.count(tag)) continue;
    r.volume_checked_materials.push_back(tag);
    const auto d = r.material_volume.find(tag), p = r.primal_material_volume.find(tag);
    const double dual = d == r.material_volume.end() ? 0.0 : d->second;
    const double prim = p == r.primal_material_volume.end() ? 0.0 : p->second;
    const double scale = std::max(std::fabs(dual), std::fabs(prim));
    const double rel = scale > 0 ? std::fabs(dual - prim) / scale : 0.0;
    if (!(rel <= tol)) r.volume_mismatches.push_back({tag, dual, prim, rel});
  }
}

}  // namespace

PrimalReference primal_reference(const ClassifiedTetMesh& primal) {
  PrimalReference ref;
  for (std::size_t v = 0; v < primal.num_vertices(); ++v)
    if (const ModelRef c = primal.vertex_class(VertexId(v)); c.dim == 0) {
      const Point3& x = primal.point(VertexId(v));
      ref.model_vertices.insert({c.tag, x.x, x.y, x.z});
    }
  for (const ModelEntity& v : primal.model().entities[0])
    for (std::int32_t e : v.bounds) ref.edge_vertex.insert({e, v.tag});
  for (int dim = 0; dim < 3; ++dim)
    for (const ModelEntity& e : primal.model().entities[dim]) ref.entities[dim].push_back(e.tag);
  for (std::size_t t = 0; t < primal.num_tets(); ++t)
    ref.material_volume[primal.region(TetId(t))] += primal.tet_volume(TetId(t));
  ref.curved_regions = regions_with_curved_faces(primal);
  return ref;
}

namespace {

// validate() against `primal` (null: no model or volume check).
ValidationReport validate_against(const PolyMesh& pm, const PrimalReference* primal, double volume_rel_tol) {
  ValidationReport r;
  r.cells = pm.num_cells();
  r.faces = pm.num_faces();
  r.points = pm.num_points();
  std::vector<char> status = check_faces(pm, r);
  check_half_face_references(pm, r, status);
  list_error_faces(status, r);
  check_cells(pm, status, r);
  if (primal) {
    check_model_entities(pm, status, *primal, r);
    check_volumes(*primal, volume_rel_tol, r);
  }
  return r;
}

}  // namespace

ValidationReport validate(const PolyMesh& pm, const PrimalReference& primal, double volume_rel_tol) {
  return validate_against(pm, &primal, volume_rel_tol);
}

ValidationReport validate(const PolyMesh& pm, const ClassifiedTetMesh* primal, double volume_rel_tol) {
  if (!primal) return validate_against(pm, nullptr, volume_rel_tol);
  const PrimalReference ref = primal_reference(*primal);
  return validate_against(pm, &ref, volume_rel_tol);
}

namespace {

std::string cell_name(CellId c) { return c.valid() ? "cell " + std::to_string(c.idx) : std::string("no cell"); }

Defect open_cells_defect(const ValidationReport& r) {
  Defect d{"open_cells",
           "cells not closed (an edge of their faces not used once each way: a face missing or reversed)",
           r.cells - r.closed_cells, {}};
  for (CellId c : r.open_cells) {
    const bool reversed = std::binary_search(r.misoriented_list.begin(), r.misoriented_list.end(), c);
    d.items.push_back(cell_name(c) + (reversed ? " (a face reversed)" : ""));
  }
  return d;
}

Defect face_errors_defect(const ValidationReport& r) {
  Defect d{"face_errors",
           "faces or face lists broken (< 3 points, a repeated or unknown point, a wrong owner, neighbour or kind, "
           "a face side listed by no cell, twice or by another cell)",
           r.error_face_count + r.error_cell_count, {}};
  for (FaceId f : r.error_faces) d.items.push_back("face " + std::to_string(f.idx));
  for (CellId c : r.error_cells) d.items.push_back(cell_name(c) + " (lists a face side not its own)");
  return d;
}

}  // namespace

std::vector<Defect> ValidationReport::defects() const {
  std::vector<Defect> out;
  if (closed_cells != cells) out.push_back(open_cells_defect(*this));
  if (face_errors > 0) out.push_back(face_errors_defect(*this));
  if (!missing_model_entities.empty())
    out.push_back({"missing_model_entities", "model entities with no dual point, edge or face on them",
                   missing_model_entities.size(), missing_model_entities});
  if (!volume_mismatches.empty()) {
    Defect d{"volume_mismatches", "materials whose dual volume differs from the primal's beyond the tolerance",
             volume_mismatches.size(), {}};
    for (const VolumeMismatch& m : volume_mismatches) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "material %d: dual %.17g, primal %.17g (relative difference %.3g)", m.material,
                    m.dual, m.primal, m.rel_diff);
      d.items.push_back(buf);
    }
    out.push_back(std::move(d));
  }
  return out;
}

std::string defect_line(const Defect& d, std::size_t shown) {
  std::string s = d.check + ": " + std::to_string(d.count) + " " + d.meaning;
  const std::size_t n = std::min(shown, d.items.size());
  for (std::size_t i = 0; i < n; ++i) s += (i == 0 ? ": " : ", ") + d.items[i];
  if (d.count > n) s += (n == 0 ? ": " : ", ") + std::string("and ") + std::to_string(d.count - n) + " more";
  return s;
}

std::string defects_sentence(const std::vector<Defect>& defects, std::size_t shown) {
  std::string s;
  for (const Defect& d : defects) s += (s.empty() ? "" : "; ") + defect_line(d, shown);
  return s;
}

Json defects_json(const std::vector<Defect>& defects) {
  Json a = Json::array();
  for (const Defect& d : defects) {
    Json o = Json::object();
    o.set("check", d.check);
    o.set("meaning", d.meaning);
    o.set("count", d.count);
    Json items = Json::array();
    for (const std::string& i : d.items) items.push(i);
    o.set("items", items);
    a.push(o);
  }
  return a;
}

Json volume_mismatches_json(const std::vector<VolumeMismatch>& mismatches) {
  Json mism = Json::array();
  for (const VolumeMismatch& m : mismatches) {
    Json o = Json::object();
    o.set("material", m.material);
    o.set("dual", m.dual);
    o.set("primal", m.primal);
    o.set("rel_diff", m.rel_diff);
    mism.push(o);
  }
  return mism;
}

Json ValidationReport::to_json() const {
  Json j = Json::object();
  j.set("cells", cells);
  j.set("faces", faces);
  j.set("points", points);
  j.set("closed_cells", closed_cells);
  j.set("manifold_cells", manifold_cells);
  j.set("slit_cells", slit_cells);
  j.set("misoriented_cells", misoriented_cells);
  j.set("face_errors", face_errors);
  j.set("negative_volume_cells", negative_volume_cells);
  Json mv = Json::array();
  for (auto& [tag, v] : material_volume) {
    Json o = Json::object();
    o.set("tag", tag);
    o.set("volume", v);
    if (auto p = primal_material_volume.find(tag); p != primal_material_volume.end()) o.set("primal_volume", p->second);
    mv.push(o);
  }
  j.set("material_volumes", mv);
  Json miss = Json::array();
  for (auto& s : missing_model_entities) miss.push(s);
  j.set("missing_model_entities", miss);
  Json checked = Json::array();
  for (std::int32_t tag : volume_checked_materials) checked.push(tag);
  j.set("volume_checked_materials", checked);
  j.set("volume_rel_tol", volume_rel_tol);
  j.set("volume_mismatches", volume_mismatches_json(volume_mismatches));
  j.set("ok", ok());
  j.set("geometry_ok", geometry_ok());
  return j;
}

}  // namespace polydual
