// The model facetisation of a classified primal (the paper's "original
// facetization", 3.3): the triangles on model faces and the segments on
// model edges, each with its model tag and its id in the primal (the
// numbering PointOrigin uses), over the primal's vertex coordinates. The
// optimiser's boundary constraints (optim/boundary.h) read it instead of the
// tet mesh: it is all they need of it, and any primal (tets or other cells,
// a surface mesh) has one.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/handles.h"
#include "core/vec3.h"
#include "mesh/classified_tet_mesh.h"
#include "mesh/primal_mesh.h"

namespace polydual {

struct ModelFacet {
  std::array<VertexId, 3> v;  // a segment's v[2] is invalid
  std::int32_t tag = 0;       // its model face's or model edge's tag
  std::uint32_t src = 0;      // its TriId (triangles) or EdgeId (segments) in the primal
};

struct ModelFacets {
  std::vector<Point3> points;          // the primal's vertices, by VertexId
  std::vector<ModelFacet> triangles;   // the triangles on model faces, increasing src
  std::vector<ModelFacet> segments;    // the edges on model edges, increasing src
  // The edges inside model faces (classified dim 2), increasing src: the
  // own-primitive constraints of the keep mode move an edge's midpoint on it.
  std::vector<ModelFacet> face_edges;
};

// Built once from the classified primal.
ModelFacets model_facets(const ClassifiedTetMesh& m);

// The same for a volume PrimalMesh, src in its numbering (PrimalFaceId,
// EdgeId: what the mixed dual's PointOrigin ids name). A quadrangle (a, b, c,
// d) on a model face becomes the two triangles (a, b, c) and (a, c, d), both
// with the quadrangle's face id as src (consecutive: triangles stay sorted by
// src, and an origin lookup finds the first, which holds the quadrangle's
// centre when it is planar: the mean lies on the diagonal a-c). A surface
// primal (dim() == 2) has no model faces in this sense: empty triangles.
ModelFacets model_facets(const PrimalMesh& m);

}  // namespace polydual
