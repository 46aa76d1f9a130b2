#include "split/warm_start.h"

#include <algorithm>
#include <unordered_map>

#include "dual/cut_topology.h"
#include "dual/sides.h"

namespace polydual {

namespace {
constexpr std::uint32_t kNone = 0xfffffffeu, kShared = 0xffffffffu;

// One slot per primal entity (vertices, edges, triangles, tets, in this
// order): the dense index of a point origin.
struct OriginSlots {
  std::size_t base[5];
  explicit OriginSlots(const ClassifiedTetMesh& m) {
    base[0] = 0;
    base[1] = m.num_vertices();
    base[2] = base[1] + m.num_edges();
    base[3] = base[2] + m.num_triangles();
    base[4] = base[3] + m.num_tets();
  }
  std::size_t size() const { return base[4]; }
  // The slot of o, or size() for an origin that names no entity of the mesh.
  std::size_t of(PointOrigin o) const {
    if (o.dim < 0 || o.id >= base[o.dim + 1] - base[o.dim]) return size();  // dim <= 3 (3 bits)
    return base[o.dim] + o.id;
  }
};

// Per slot, the one point of `mesh` made from it, kShared for several, kNone
// for none.
std::vector<std::uint32_t> points_of_origins(const PolyMesh& mesh, const OriginSlots& slots) {
  std::vector<std::uint32_t> where(slots.size(), kNone);
  for (std::size_t i = 0; i < mesh.points.size(); ++i) {
    const std::size_t s = slots.of(mesh.point_origin[i]);
    if (s == slots.size()) continue;
    where[s] = where[s] == kNone ? std::uint32_t(i) : kShared;
  }
  return where;
}
}  // namespace

std::size_t warm_start(PolyMesh& fresh, const PolyMesh& old, const ClassifiedTetMesh& m, const VertexCuts& cuts,
                       std::vector<PointId>* from_old) {
  if (from_old) from_old->clear();
  if (fresh.point_origin.size() != fresh.points.size() || old.point_origin.size() != old.points.size()) return 0;
  const OriginSlots slots(m);
  const std::vector<std::uint32_t> where = points_of_origins(old, slots);
  if (from_old) from_old->assign(fresh.points.size(), PointId::invalid());
  std::vector<std::uint8_t> taken;  // per old point, how many fresh points name its origin (saturating)
  if (from_old) taken.assign(old.points.size(), 0);
  std::size_t moved = 0;
  for (std::size_t i = 0; i < fresh.points.size(); ++i) {
    const std::size_t s = slots.of(fresh.point_origin[i]);
    if (s == slots.size()) continue;
    const std::uint32_t w = where[s];
    if (w == kNone || w == kShared) continue;
    if (from_old) {
      (*from_old)[i] = PointId(w);
      taken[w] = std::uint8_t(std::min(2, taken[w] + 1));
    }
    if (pinned(m, &cuts, fresh.point_origin[i])) continue;
    fresh.points[i] = old.points[w];
    ++moved;
  }
  // One point each side: an origin shared by several fresh points maps none
  // of them, so that from_old is one-to-one (split/recheck.h).
  if (from_old)
    for (PointId& q : *from_old)
      if (q.valid() && taken[q.idx] > 1) q = PointId::invalid();
  return moved;
}

namespace {
// Per side of (m, cuts), the side of (m, no cuts) holding the same tets; and
// those sides' vertices (cut.cell_vertex) in *vertex when not null.
std::vector<CellId> side_origins(const ClassifiedTetMesh& m, const VertexCuts& cuts, std::vector<VertexId>* vertex) {
  const VertexSides plain = compute_sides(m, nullptr);
  VertexSides cut = compute_sides(m, &cuts);
  std::vector<CellId> origin(cut.num_cells, CellId::invalid());
  for (std::size_t vi = 0; vi < m.num_vertices(); ++vi) {
    const VertexId v(vi);
    for (TetId t : m.vertex_tets(v)) origin[cut.cell(t, v).idx] = plain.cell(t, v);
  }
  if (vertex) *vertex = std::move(cut.cell_vertex);
  return origin;
}
}  // namespace

std::vector<CellId> cut_cell_origins(const ClassifiedTetMesh& m, const VertexCuts& cuts, const PolyMesh& mesh) {
  std::vector<VertexId> vertex;
  std::vector<CellId> origin = side_origins(m, cuts, &vertex);
  if (origin.size() != mesh.num_cells()) return {};
  for (std::size_t c = 0; c < origin.size(); ++c)
    if (!origin[c].valid() || mesh.cell_primal[c] != VertexId(m.input_vertex(vertex[c]))) return {};
  return origin;
}

std::vector<CellId> cut_cell_origins(const ClassifiedTetMesh& m, const VertexCuts& cuts) {
  return side_origins(m, cuts, nullptr);
}

}  // namespace polydual
