#include "pipeline/check.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <numeric>

#include "core/error.h"
#include "io/vtu_poly_writer.h"
#include "predicates/predicates.h"

namespace polydual {


namespace {
// invalid_cells and decomposition_tets from r.verdicts.
void count_verdicts(CheckResult& r) {
  r.invalid_cells = 0;
  r.decomposition_tets = 0;
  for (const CellVerdict& v : r.verdicts) {
    r.invalid_cells += !v.valid;
    r.decomposition_tets += static_cast<std::uint64_t>(v.total_tets);
  }
}
}  // namespace

CheckResult check_with_known_verdicts(const PolyMesh& mesh, const ClassifiedTetMesh* primal, CheckResult known) {
  const auto t0 = std::chrono::steady_clock::now();
  if (known.verdicts.size() != mesh.num_cells() || known.cell_exact.size() != mesh.num_cells())
    return check_mesh(mesh, primal, true);
  CheckResult r = std::move(known);
  r.validation = validate(mesh, primal);
  count_verdicts(r);
  r.exact_fallbacks = std::accumulate(r.cell_exact.begin(), r.cell_exact.end(), std::uint64_t{0});
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

CheckResult check_mesh(const PolyMesh& mesh, const ClassifiedTetMesh* primal, bool with_validation) {
  const auto t0 = std::chrono::steady_clock::now();
  CheckResult r;
  if (with_validation) r.validation = validate(mesh, primal);
  // The exact fallbacks are counted by shared counters (predicates.h): read
  // the difference so concurrent checks of other meshes do not reset them.
  const std::uint64_t exact0 = predicate_counters().star_exact.load();
  std::vector<std::uint32_t> all(mesh.num_cells());
  std::iota(all.begin(), all.end(), 0u);
  r.verdicts.resize(mesh.num_cells());
  r.cell_exact.assign(mesh.num_cells(), 0);
  star_shaped_verdicts_of(mesh, all, r.verdicts, r.cell_exact);
  r.exact_fallbacks = predicate_counters().star_exact.load() - exact0;
  count_verdicts(r);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

Json CheckResult::to_json() const {
  Json j = Json::object();
  j.set("invalid_cells", invalid_cells);
  j.set("decomposition_tets", decomposition_tets);
  j.set("exact_fallbacks", exact_fallbacks);
  j.set("validation", validation.to_json());
  return j;
}

void require_valid_mesh(const CheckResult& c, const std::string& source) {
  const std::vector<Defect> defects = c.validation.defects();
  if (c.invalid_cells == 0 && defects.empty()) return;
  std::string what;
  if (!defects.empty()) what = "the mesh is not sound: " + defects_sentence(defects) + (c.invalid_cells ? "; " : "");
  if (c.invalid_cells > 0) {
    what += std::to_string(c.invalid_cells) + " cells are invalid (exact star test):";
    std::size_t listed = 0;
    for (std::size_t k = 0; k < c.verdicts.size() && listed < kListedDefects; ++k)
      if (!c.verdicts[k].valid) what += std::string(listed++ ? "," : "") + " cell " + std::to_string(k);
    if (c.invalid_cells > listed) what += " and " + std::to_string(c.invalid_cells - listed) + " more";
  }
  throw InputError(source, "", what);
}

namespace {

std::string xyz(const Point3& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.17g, %.17g, %.17g)", p.x, p.y, p.z);
  return buf;
}

// The primal's internal vertex of each cell (its primal vertex is in the
// input numbering), after checking that the cells and the primal name the
// same vertices.
std::vector<VertexId> primal_vertex_of_cells(const PolyMesh& mesh, const std::string& mesh_source,
                                             const ClassifiedTetMesh& primal) {
  const std::string& src = primal.source();
  const std::string not_of = "is not the tet mesh " + mesh_source + " is the dual of: ";
  std::vector<VertexId> internal;  // by input number
  for (std::size_t v = 0; v < primal.num_vertices(); ++v) {
    const std::uint32_t in = primal.input_vertex(VertexId(v));
    if (in >= internal.size()) internal.resize(in + 1, VertexId::invalid());
    internal[in] = VertexId(v);
  }
  std::vector<char> named(internal.size(), 0);
  std::vector<VertexId> of_cell(mesh.num_cells());
  for (std::size_t c = 0; c < mesh.num_cells(); ++c) {
    const VertexId in = mesh.cell_primal[c];
    if (!in.valid())
      throw InputError(src, "", not_of + "cell " + std::to_string(c) + " of " + mesh_source +
                                    " names no primal vertex (no 'primal_vertex' array?)");
    if (in.idx >= internal.size() || !internal[in.idx].valid())
      throw InputError(src, "", not_of + "cell " + std::to_string(c) + " of " + mesh_source + " names primal vertex " +
                                    std::to_string(in.idx) + " (0-based), which " + src + " does not have (" +
                                    std::to_string(primal.num_vertices()) + " vertices in tets)");
    named[in.idx] = 1;
    of_cell[c] = internal[in.idx];
  }
  for (std::size_t in = 0; in < internal.size(); ++in)
    if (internal[in].valid() && !named[in])
      throw InputError(src, "", not_of + "its vertex " + std::to_string(in) + " (0-based) has no cell in " +
                                    mesh_source + " (" + std::to_string(primal.num_vertices()) +
                                    " vertices in tets; the cells name fewer)");
  return of_cell;
}

// Every dual point on a model vertex at the primal vertex of one of its
// cells, compared exactly; every primal vertex in its cell's grown box.
void check_primal_positions(const PolyMesh& mesh, const std::string& mesh_source, const ClassifiedTetMesh& primal,
                            const std::vector<VertexId>& of_cell) {
  const std::string& src = primal.source();
  const std::string not_of = "is not the tet mesh " + mesh_source + " is the dual of: ";
  std::vector<char> at_vertex(mesh.num_points(), 0);
  CellPointScan scan(mesh);
  for (std::size_t c = 0; c < mesh.num_cells(); ++c) {
    const Point3 v = primal.point(of_cell[c]);
    Point3 lo = v, hi = v;
    bool first = true;
    for (PointId p : scan(CellId(c))) {
      const Point3& x = mesh.points[p.idx];
      if (x.x == v.x && x.y == v.y && x.z == v.z) at_vertex[p.idx] = 1;
      lo = first ? x : Point3{std::min(lo.x, x.x), std::min(lo.y, x.y), std::min(lo.z, x.z)};
      hi = first ? x : Point3{std::max(hi.x, x.x), std::max(hi.y, x.y), std::max(hi.z, x.z)};
      first = false;
    }
    const Point3 grow = hi - lo;
    if (!first && !(v.x >= lo.x - grow.x && v.x <= hi.x + grow.x && v.y >= lo.y - grow.y && v.y <= hi.y + grow.y &&
                    v.z >= lo.z - grow.z && v.z <= hi.z + grow.z))
      throw InputError(src, "", not_of + "the primal vertex " + std::to_string(mesh.cell_primal[c].idx) + " at " +
                                    xyz(v) + " is far from its cell " + std::to_string(c) + " of " + mesh_source +
                                    ", which spans " + xyz(lo) + " to " + xyz(hi));
  }
  for (std::size_t p = 0; p < mesh.num_points(); ++p)
    if (mesh.point_class[p].dim == 0 && !at_vertex[p])
      throw InputError(src, "", not_of + "point " + std::to_string(p) + " of " + mesh_source + " at " +
                                    xyz(mesh.points[p]) +
                                    " lies on a model vertex, but no cell holding it has its primal vertex there");
}

}  // namespace

void require_primal_of(const PolyMesh& mesh, const std::string& mesh_source, const ClassifiedTetMesh& primal) {
  check_primal_positions(mesh, mesh_source, primal, primal_vertex_of_cells(mesh, mesh_source, primal));
}

std::vector<CellField> verdict_fields(const std::vector<CellVerdict>& verdicts) {
  std::vector<std::int32_t> valid(verdicts.size()), bad(verdicts.size());
  for (std::size_t c = 0; c < verdicts.size(); ++c) {
    valid[c] = verdicts[c].valid;
    bad[c] = verdicts[c].bad_tets;
  }
  return {CellField{"valid", std::move(valid)}, CellField{"bad_tets", std::move(bad)}};
}

}  // namespace polydual
