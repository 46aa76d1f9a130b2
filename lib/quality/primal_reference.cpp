#include "quality/primal_reference.h"

#include <map>

#include "predicates/predicates.h"

namespace polydual {

namespace {

// Signed volume of cell c (primal_reference's rule; outward loops give
// positive tets).
double primal_cell_volume(const PrimalMesh& m, PrimalCellId c) {
  const auto cv = m.cell_vertices(c);
  const Point3 g = vertex_mean(m, cv);
  double vol = 0;
  const CellDescriptor& d = m.cell_descriptor(c);
  for (int i = 0; i < d.num_faces; ++i) {
    const int n = d.face_size[i];
    Point3 fc{0, 0, 0};
    for (int k = 0; k < n; ++k) fc = fc + m.point(cv[d.faces[i][k]]);
    fc = fc * (1.0 / double(n));
    for (int k = 0; k < n; ++k) {
      const Point3 &a = m.point(cv[d.faces[i][k]]), &b = m.point(cv[d.faces[i][(k + 1) % n]]);
      vol += dot(b - a, cross(fc - a, g - a));
    }
  }
  return -vol / 6.0;
}

// Regions bounded (external or interface) by a model face that is not planar.
std::set<std::int32_t> regions_with_curved_faces(const PrimalMesh& m) {
  std::map<std::int32_t, PrimalFaceId> first;
  std::set<std::int32_t> curved_tags, regions;
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    const PrimalFaceId fid(f);
    if (m.face_class(fid).dim != 2) continue;
    const auto [it, fresh] = first.emplace(m.face_class(fid).tag, fid);
    const auto base = m.face_vertices(it->second);
    for (VertexId v : m.face_vertices(fid))
      if (orient3d(m.point(base[0]), m.point(base[1]), m.point(base[2]), m.point(v)) != Sign::Zero)
        curved_tags.insert(m.face_class(fid).tag);
  }
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    const PrimalFaceId fid(f);
    if (m.face_class(fid).dim != 2 || !curved_tags.count(m.face_class(fid).tag)) continue;
    const PrimalCellId c0 = m.face_cell(fid, 0), c1 = m.face_cell(fid, 1);
    if (c1.valid() && m.cell_class(c0).tag == m.cell_class(c1).tag) continue;  // a fracture: cancels inside
    regions.insert(m.cell_class(c0).tag);
    if (c1.valid()) regions.insert(m.cell_class(c1).tag);
  }
  return regions;
}

// The model entities of the primal: model vertices, edge-vertex incidences
// and the tags of every dimension.
void model_entities(const PrimalMesh& m, PrimalReference& ref) {
  std::array<std::set<std::int32_t>, 3> tags;
  for (std::size_t v = 0; v < m.num_vertices(); ++v)
    if (const ModelRef c = m.vertex_class(VertexId(v)); c.dim == 0) {
      const Point3& x = m.point(VertexId(v));
      ref.model_vertices.insert({c.tag, x.x, x.y, x.z});
      tags[0].insert(c.tag);
    }
  for (std::size_t e = 0; e < m.num_edges(); ++e) {
    const ModelRef c = m.edge_class(EdgeId(e));
    if (c.dim != 1) continue;
    tags[1].insert(c.tag);
    for (VertexId v : m.edge(EdgeId(e)))
      if (const ModelRef vc = m.vertex_class(v); vc.dim == 0) ref.edge_vertex.insert({c.tag, vc.tag});
  }
  for (std::size_t f = 0; f < m.num_faces(); ++f)
    if (const ModelRef c = m.face_class(PrimalFaceId(f)); c.dim == 2) tags[2].insert(c.tag);
  for (int dim = 0; dim < 3; ++dim) ref.entities[dim].assign(tags[dim].begin(), tags[dim].end());
}

}  // namespace

PrimalReference primal_reference(const PrimalMesh& m) {
  PrimalReference ref;
  model_entities(m, ref);
  for (std::size_t c = 0; c < m.num_cells(); ++c)
    ref.material_volume[m.cell_class(PrimalCellId(c)).tag] += primal_cell_volume(m, PrimalCellId(c));
  ref.curved_regions = regions_with_curved_faces(m);
  return ref;
}

}  // namespace polydual
