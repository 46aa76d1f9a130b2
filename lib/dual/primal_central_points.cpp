// The per-type central point rule of primal_central_points.h.
#include "dual/primal_central_points.h"

#include "predicates/predicates.h"

namespace polydual {
namespace {

// EXACT: p lies strictly on the inner side of every triangle (a, b, c) of
// consecutive vertices of every face loop of c (both fans of a quadrangle).
bool strictly_inside(const PrimalMesh& m, PrimalCellId c, const Point3& p) {
  const CellDescriptor& d = m.cell_descriptor(c);
  const auto cv = m.cell_vertices(c);
  for (int i = 0; i < d.num_faces; ++i) {
    const int n = d.face_size[i];
    for (int k = 0; k < (n == 3 ? 1 : n); ++k) {
      const Point3& a = m.point(cv[d.faces[i][k]]);
      const Point3& b = m.point(cv[d.faces[i][(k + 1) % n]]);
      const Point3& e = m.point(cv[d.faces[i][(k + 2) % n]]);
      if (orient3d(a, b, e, p) != Sign::Negative) return false;  // outward loops: inside is negative
    }
  }
  return true;
}

// A prism's central point: the midpoint of its two triangles' central points
// (each its circumcentre when it holds it, decided exactly). On a right prism
// (an extruded triangle, as boundary layers and extruded meshes are) that is
// the circumcentre of all six vertices, so the dual of an extruded Delaunay
// triangulation is the extruded Voronoi diagram, orthogonal to the primal
// edges as the tet dual is where it is well centred. The vertex mean when
// the midpoint is not strictly inside the prism (EXACT test).
CentralPoint prism_central_point(const PrimalMesh& m, PrimalCellId c) {
  const auto v = m.cell_vertices(c);
  const CentralPoint lo = triangle_central_point(m.point(v[0]), m.point(v[1]), m.point(v[2]));
  const CentralPoint hi = triangle_central_point(m.point(v[3]), m.point(v[4]), m.point(v[5]));
  CentralPoint out{(lo.p + hi.p) * 0.5, false, 0};
  if (strictly_inside(m, c, out.p)) {
    out.well_centred = true;
    return out;
  }
  out.p = vertex_mean(m, v);
  out.well_centred = strictly_inside(m, c, out.p);
  return out;
}

}  // namespace

CentralPoint cell_central_point(const PrimalMesh& m, PrimalCellId c) {
  const auto v = m.cell_vertices(c);
  switch (m.cell_type(c)) {
    case CellType::Tet: return tet_central_point(m.point(v[0]), m.point(v[1]), m.point(v[2]), m.point(v[3]));
    case CellType::Triangle: return triangle_central_point(m.point(v[0]), m.point(v[1]), m.point(v[2]));
    case CellType::Quad: return {vertex_mean(m, v), false, 0};  // inside-ness needs the surface's orientation
    case CellType::Prism: return prism_central_point(m, c);
    default: break;
  }
  CentralPoint out{vertex_mean(m, v), false, 0};
  out.well_centred = strictly_inside(m, c, out.p);
  return out;
}

CentralPoint face_central_point(const PrimalMesh& m, PrimalFaceId f) {
  const auto v = m.face_vertices(f);
  if (v.size() == 3) return triangle_central_point(m.point(v[0]), m.point(v[1]), m.point(v[2]));
  return {vertex_mean(m, v), false, 0};
}

}  // namespace polydual
