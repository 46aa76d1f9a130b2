#include "pipeline/check.h"

#include <algorithm>
#include <cstdio>

#include "core/error.h"
#include "io/vtu_poly_writer.h"
#include "optim/tet_optimize.h"

namespace polydual {

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

ClassifiedTetMesh primal_of_dual(const PolyMesh& mesh, ClassifiedTetMesh primal, const TetOptParams& tetopt) {
  std::uint32_t named = 0, have = 0;
  for (VertexId v : mesh.cell_primal)
    if (v.valid()) named = std::max(named, v.idx + 1);
  for (std::size_t v = 0; v < primal.num_vertices(); ++v) have = std::max(have, primal.input_vertex(VertexId(v)) + 1);
  if (named <= have || !tetopt.enabled || !tetopt.steiner.enabled) return primal;
  // convert's tet stage, with its ratio for an optimised dual or the one
  // without an optimiser: the one that gives the dual's vertices. Its moves
  // too: an inserted vertex moves far from the centroid it was put at.
  for (double ratio : {tetopt.steiner.ratio, tetopt.steiner.ratio_without_optimiser}) {
    TetOptParams p = tetopt;
    p.steiner.ratio = ratio;
    ClassifiedTetMesh m = optimize_tets(primal, p);
    if (have + m.num_vertices() - primal.num_vertices() == named) return m;
  }
  return primal;  // require_primal_of names the mismatch
}

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
