// Element quality from corner condition numbers (paper 3.2, design §6).
// A cell's quality is the mean of kappa/3 over its corners under Q1 (symmetric
// decomposition corners at the original vertices) or Q2 (region-centre corners):
// 1 would be all right unit corners; larger is worse. Note that neither metric
// gives 1 on a cube: Q1 corners mix F and R, Q2 corners point at R
// (unit cube: Q1 = 1.8708, Q2 = 1.5635; proofs/quality.md).
#pragma once
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "core/json.h"
#include "mesh/poly_mesh.h"
#include "quality/stencil.h"

namespace polydual {

// Name of a metric ("q1" / "q2").
const char* metric_name(Metric m);

// Quality of cell c: mean kappa/3 over its corners, or +infinity if some corner
// has V <= 0 ("tangled"; for Q1 that is exactly a non-positive decomposition
// tet evaluated in doubles).
double cell_quality(const MeshStencil& s, std::uint32_t c, Metric m, std::span<const Point3> points);
std::vector<double> cell_qualities(const MeshStencil& s, Metric m, std::span<const Point3> points);

struct QualityStats {
  Metric metric = Metric::Q1;
  std::size_t cells = 0;    // cells measured
  std::size_t tangled = 0;  // cells with a corner V <= 0 (excluded below)
  // Of the tangled cells, those the exact star test calls valid: a corner
  // whose volume rounds to <= 0 in doubles (kappa unbounded), not an
  // inverted cell. Filled by callers that hold the exact verdicts (the
  // optimiser's records); 0 otherwise.
  std::size_t degenerate = 0;
  double min = 0, mean = 0, max = 0;  // over untangled cells, kappa/3 (>= 1)
  // histogram[i] counts untangled cells with bin_edges[i] <= q < bin_edges[i+1]
  // (the last bin is open).
  std::vector<double> bin_edges;
  std::vector<std::size_t> histogram;
  Json to_json() const;
};

QualityStats quality_stats(std::span<const double> cell_quality, Metric m);
QualityStats quality_stats(const PolyMesh& mesh, Metric m);

// V0 of eq. 3 per cell: the mean |V| over the cell's corners (metric m) at the
// given coordinates, floored at 1e-3 x the mesh-wide mean so a collapsed cell
// still has a positive scale. The optimisers compute it once at the start so the
// objective is one fixed function during a run.
std::vector<double> cell_reference_volumes(const MeshStencil& s, Metric m,
                                           std::span<const Point3> points);
// The same reference volumes and, from the same pass over the corners, each
// cell's cell_quality (bit for bit) into *quality.
std::vector<double> cell_reference_volumes(const MeshStencil& s, Metric m, std::span<const Point3> points,
                                           std::vector<double>* quality);

// Sum of kappa_mod over the corners of cell c (the objective's cell term, design §7).
double cell_energy(const MeshStencil& s, std::uint32_t c, Metric m, std::span<const Point3> points,
                   double V0, double c_delta);
// cell_energy, and cell_quality into *quality, from one pass over the corners
// (each bit for bit the value of its own function).
double cell_energy_and_quality(const MeshStencil& s, std::uint32_t c, Metric m, std::span<const Point3> points,
                               double V0, double c_delta, double* quality);

}  // namespace polydual
