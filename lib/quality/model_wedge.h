// The shape of the model at a primal vertex as one material's tets see it:
// the solid angle they fill at the vertex and the smallest dihedral angle
// they fill at a model edge through it. A dual cell whose primal vertex sits
// in a thin wedge (two model faces meeting at a few degrees: a sphere tangent
// to a plane, a cusp of a fragmented CAD model) cannot be well shaped: it
// must fit between faces it may not leave. The convert summary reports these
// angles for the cells left above the quality bound, so that a user sees
// which cells the model itself forbids from meeting it.
//
// Measurements in floating point (angles from the tets' coordinates); they
// decide nothing.
#pragma once
#include <cstdint>

#include "core/classification.h"
#include "core/handles.h"
#include "mesh/classified_tet_mesh.h"

namespace polydual {

struct VertexWedge {
  // Sum over the material's tets at v of their solid angles at v, steradians
  // (4 pi inside the material, 2 pi on a flat model face, pi/2 at a cube's corner).
  double solid_angle_sr = 0;
  // The smallest, over the primal edges through v on a model edge, of the
  // sum of the material's tets' dihedral angles at that edge, degrees
  // (360 inside, 180 along a flat face, 90 at a cube's edge); 360 when no
  // model edge passes through v.
  double min_wedge_deg = 360;
  ModelRef wedge_edge;  // that edge's model edge (invalid when none)
};

VertexWedge vertex_wedge(const ClassifiedTetMesh& m, VertexId v, std::int32_t material);

}  // namespace polydual
