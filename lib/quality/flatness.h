// Flatness of the dual's faces (measure only): how far a
// polygon face is from planar, as OpenFOAM's checkMesh measures it and as a
// distance to a best-fit plane.
//
// OpenFOAM (primitiveMeshFaceCentresAndAreas, primitiveMeshTools::faceFlatness):
//   m = mean of the face's points; fan triangles t_i = (p_i, p_i+1, m) with
//   area vectors n_i = (p_i+1 - p_i) x (m - p_i) / 2; area vector
//   S = sum n_i; face centre c = sum a_i g_i / sum a_i with g_i the centroid of
//   t_i and a_i = n_i . S/|S| (a triangle's centre is its mean, S = n_0);
//   flatness = |S| / sum_i |(p_i+1 - p_i) x (c - p_i)| / 2, the projected over
//   the actual area: 1 for a planar convex face, smaller when warped (checkMesh
//   calls faces below 0.8 warped).
// Best-fit plane: through the mean of the points, normal the eigenvector of
// the smallest eigenvalue of their scatter matrix (least squares); deviation =
// largest |distance| of a point to it divided by the face's diameter (largest
// distance between two of its points).
#pragma once
#include <span>

#include "core/json.h"
#include "mesh/poly_mesh.h"

namespace polydual {

struct FaceFlatness {
  double flatness = 1;   // OpenFOAM's projected / actual area, in (0, 1]
  double deviation = 0;  // best-fit plane distance / diameter, >= 0
};

// Of the polygon (p_0 .. p_{n-1}), n >= 3. A polygon of zero actual area gives
// flatness 1 and deviation 0 (nothing to measure).
FaceFlatness face_flatness(std::span<const Point3> polygon);
// Its flatness alone (no best-fit plane): cheap enough for an objective.
double flatness_ratio(std::span<const Point3> polygon);

struct FlatnessStats {
  std::size_t faces = 0;
  double min_flatness = 1, mean_flatness = 1;
  std::size_t warped = 0;  // flatness < kWarped (checkMesh's threshold)
  double max_deviation = 0, mean_deviation = 0;
  static constexpr double kWarped = 0.8;
  Json to_json() const;
};

// Over every face of `mesh` (parallel per face, serial sums: deterministic).
FlatnessStats flatness_stats(const PolyMesh& mesh);

}  // namespace polydual
