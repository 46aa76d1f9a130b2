#include "optim/tet_ops.h"

#include <algorithm>
#include <stdexcept>

#include "optim/tet_optimize.h"

namespace polydual::tetops {

double tet_quality_of(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  return tet_quality(a, b, c, d);
}

ConstrainedEdges::ConstrainedEdges(const ClassifiedTetMesh& m) {
    for (std::size_t e = 0; e < m.num_edges(); ++e) {
      if (m.edge_class(EdgeId(e)).dim >= 3) continue;
      const auto [a, b] = m.edge(EdgeId(e));
      entries_.push_back({key(a.idx, b.idx), m.edge_class(EdgeId(e))});
    }
    std::sort(entries_.begin(), entries_.end(), [](const Entry& x, const Entry& y) { return x.key < y.key; });
  }

const ModelRef* ConstrainedEdges::find(std::uint32_t a, std::uint32_t b) const {
    const std::uint64_t k = key(a, b);
    const auto it = std::lower_bound(entries_.begin(), entries_.end(), k,
                                     [](const Entry& x, std::uint64_t y) { return x.key < y; });
    return it != entries_.end() && it->key == k ? &it->ref : nullptr;
  }


FlipMesh::FlipMesh(const ClassifiedTetMesh& m) : pts(m.points().begin(), m.points().end()), cedges(m) {
    const std::size_t n = m.num_tets();
    tv.resize(n), nb.resize(n), ftag.resize(n), region.resize(n), input_tet.resize(n);
    version.assign(n, 0), alive.assign(n, 1);
    for (std::size_t t = 0; t < n; ++t) {
      const TetId id(t);
      for (int i = 0; i < 4; ++i) {
        tv[t][i] = m.tet(id)[i].idx;
        const TetId u = m.tet_neighbor(id, i);
        nb[t][i] = u.valid() ? 4 * u.idx + std::uint32_t(m.tet_neighbor_face(id, i)) : kNone;
        const ModelRef r = m.triangle_class(m.tet_triangle(id, i));
        ftag[t][i] = r.dim == 2 ? r.tag : kNoFace;
      }
      region[t] = m.region(id);
      input_tet[t] = m.input_tet(id);
    }
  }

// A local face's three vertices, sorted (a key to match faces).
std::array<std::uint32_t, 3> face_key(const Tet& t, int i) {
  std::array<std::uint32_t, 3> k{};
  int n = 0;
  for (int j = 0; j < 4; ++j)
    if (j != i) k[n++] = t[j];
  std::sort(k.begin(), k.end());
  return k;
}


// The faces of the cavity `old` (tets being replaced) that stay: every face
// whose neighbour is not in the cavity, with its link and model-face tag.
std::vector<OuterFace> cavity_boundary(const FlipMesh& w, std::span<const std::uint32_t> old) {
  std::vector<OuterFace> out;
  for (std::uint32_t o : old)
    for (int i = 0; i < 4; ++i) {
      const std::uint32_t n = w.nb[o][i];
      if (n != kNone && std::find(old.begin(), old.end(), n >> 2) != old.end()) continue;
      out.push_back({face_key(w.tv[o], i), n, w.ftag[o][i]});
    }
  return out;
}

// Slots for k new tets replacing `old`: the old slots first, then freed ones,
// then new slots at the end. Old slots not reused are freed.
namespace {
std::vector<std::uint32_t> take_slots(FlipMesh& w, std::span<const std::uint32_t> old, std::size_t k) {
  std::vector<std::uint32_t> slots;
  for (std::size_t j = 0; j < old.size(); ++j) {
    ++w.version[old[j]];
    if (j < k) slots.push_back(old[j]);
    else {
      w.alive[old[j]] = 0;
      w.free_slots.push_back(old[j]);
    }
  }
  while (slots.size() < k) {
    if (!w.free_slots.empty()) {
      slots.push_back(w.free_slots.back());
      w.free_slots.pop_back();
      ++w.version[slots.back()];
    } else {
      slots.push_back(std::uint32_t(w.tv.size()));
      w.tv.emplace_back(), w.nb.emplace_back(), w.ftag.emplace_back();
      w.region.push_back(0), w.input_tet.push_back(0), w.version.push_back(0), w.alive.push_back(0);
    }
  }
  return slots;
}
}  // namespace

// Replaces the tets `old` (one region, one convex cavity) by `fresh` (all
// positive, same union): relinks the cavity's boundary faces with their tags,
// links the new interior faces (no model face) and queues the boundary faces.
void replace(FlipMesh& w, std::span<const std::uint32_t> old, std::span<const Tet> fresh) {
  const std::vector<OuterFace> outer = cavity_boundary(w, old);
  const std::int32_t region = w.region[old[0]];
  const std::uint32_t input = w.input_tet[old[0]];
  const std::vector<std::uint32_t> slots = take_slots(w, old, fresh.size());
  for (std::size_t j = 0; j < fresh.size(); ++j) {
    const std::uint32_t s = slots[j];
    w.tv[s] = fresh[j], w.region[s] = region, w.alive[s] = 1;
    if (j >= old.size()) w.input_tet[s] = input;
    w.nb[s].fill(kNone);
  }
  for (std::size_t j = 0; j < fresh.size(); ++j)
    for (int i = 0; i < 4; ++i) {
      const std::uint32_t s = slots[j];
      const auto key = face_key(fresh[j], i);
      const auto it = std::find_if(outer.begin(), outer.end(), [&](const OuterFace& f) { return f.key == key; });
      if (it != outer.end()) {
        w.nb[s][i] = it->link, w.ftag[s][i] = it->tag;
        if (it->link != kNone) w.nb[it->link >> 2][it->link & 3] = 4 * s + std::uint32_t(i);
        w.queue.push_back({s, w.version[s], i});
        continue;
      }
      w.ftag[s][i] = kNoFace;
      for (std::size_t q = 0; q < fresh.size() && w.nb[s][i] == kNone; ++q)
        for (int k = 0; k < 4; ++k)
          if (q != j && face_key(fresh[q], k) == key) w.nb[s][i] = 4 * slots[q] + std::uint32_t(k);
      if (w.nb[s][i] == kNone) throw std::logic_error("delaunay_flips: a new face matches no face of the cavity");
    }
}


// The ClassifiedTetMesh of the flipped tets: live slots in order, the
// classification of vertices, model-face triangles and constrained edges
// carried over; new edges are classified on their region as classify() does.
ClassifiedTetMesh rebuild(const ClassifiedTetMesh& mesh, const FlipMesh& w) {
  std::vector<std::array<VertexId, 4>> tets;
  std::vector<std::int32_t> regions;
  std::vector<std::uint32_t> input_tet;
  std::vector<std::array<std::int32_t, 4>> tags;
  for (std::size_t s = 0; s < w.tv.size(); ++s) {
    if (!w.alive[s]) continue;
    tets.push_back({VertexId(w.tv[s][0]), VertexId(w.tv[s][1]), VertexId(w.tv[s][2]), VertexId(w.tv[s][3])});
    regions.push_back(w.region[s]);
    input_tet.push_back(w.input_tet[s]);
    tags.push_back(w.ftag[s]);
  }
  std::vector<std::uint32_t> input_vertex = mesh.input_vertices();
  if (input_vertex.empty() && !w.new_vertex_region.empty())  // identity until now
    for (std::uint32_t v = 0; v < mesh.num_vertices(); ++v) input_vertex.push_back(v);
  std::uint32_t next_input = 0;
  for (std::uint32_t i : input_vertex) next_input = std::max(next_input, i + 1);
  for (std::size_t k = 0; k < w.new_vertex_region.size(); ++k) input_vertex.push_back(next_input++);
  ClassifiedTetMesh out = TetMeshBuilder::build_topology(mesh.source(), w.pts, std::move(tets), std::move(regions),
                                                         std::move(input_vertex), std::move(input_tet));
  TetMeshBuilder::vertex_class(out) = [&] {
    std::vector<ModelRef> vc(w.pts.size());
    for (std::size_t v = 0; v < mesh.num_vertices(); ++v) vc[v] = mesh.vertex_class(VertexId(v));
    for (std::size_t k = 0; k < w.new_vertex_region.size(); ++k)
      vc[mesh.num_vertices() + k] = ModelRef{3, w.new_vertex_region[k]};
    return vc;
  }();
  auto& tf = TetMeshBuilder::triangle_face(out);
  tf.assign(out.num_triangles(), kNoFace);
  auto& ec = TetMeshBuilder::edge_class(out);
  ec.assign(out.num_edges(), ModelRef{});
  for (std::size_t t = 0; t < out.num_tets(); ++t) {
    const TetId id(t);
    for (int i = 0; i < 4; ++i) tf[out.tet_triangle(id, i).idx] = tags[t][i];
    for (int k = 0; k < 6; ++k) {
      const EdgeId e = out.tet_edge(id, k);
      const auto [a, b] = out.edge(e);
      const ModelRef* r = w.cedges.find(a.idx, b.idx);
      ec[e.idx] = r ? *r : ModelRef{3, out.region(out.edge_tet(e))};
    }
  }
  TetMeshBuilder::model(out) = mesh.model();
  TetMeshBuilder::classification_warnings(out) = mesh.classification_warnings();
  TetMeshBuilder::marker_features(out) = mesh.marker_features();
  return out;
}


}  // namespace polydual::tetops
