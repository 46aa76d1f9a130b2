// The exact star-shaped validity test (paper 3.1, design §5).
// For every face f of cell c and every edge (a,b) of f in c's outward order, the
// decomposition tet (a, b, F_f, R_c) with F = mean of f's points and R = mean of
// c's distinct points must be strictly positive (decomposition_tet_sign, exact).
#pragma once
#include <span>
#include <utility>
#include <vector>

#include "mesh/poly_mesh.h"
#include "quality/stencil.h"

namespace polydual {

struct CellVerdict {
  bool valid = true;   // every decomposition tet Positive
  int bad_tets = 0;    // tets with Zero or Negative sign
  int total_tets = 0;  // sum over the cell's faces of their edge counts
};

CellVerdict star_shaped_verdict(const PolyMesh& mesh, CellId c);
// All cells (TBB parallel, deterministic: each entry depends on its cell only).
std::vector<CellVerdict> star_shaped_verdicts(const PolyMesh& mesh);
// The verdicts of the listed cells only, into out[c] (out has one entry per
// cell of mesh; the others are left alone), and each listed cell's number of
// exact fallbacks into exact[c] (the same size; empty: not recorded). TBB
// parallel; every entry depends on its cell only.
void star_shaped_verdicts_of(const PolyMesh& mesh, std::span<const std::uint32_t> cells, std::span<CellVerdict> out,
                             std::span<std::uint32_t> exact);

// The same test on a precomputed stencil with explicit coordinates (the
// optimisers move points without rebuilding the mesh). With stop_at_first_bad the
// count stops at the first bad tet (bad_tets = 1): the fast yes/no the line
// searches need. `scratch` is reused to avoid allocations.
CellVerdict star_shaped_verdict(const MeshStencil& s, std::uint32_t c,
                                std::span<const Point3> points, bool stop_at_first_bad,
                                std::vector<Point3>& scratch);
// The same test, listing every non-positive tet as (loop j of the stencil,
// edge i of the loop: the tet (loop[i], loop[i+1], F, R)) into `bad`.
CellVerdict star_shaped_bad_tets(const MeshStencil& s, std::uint32_t c, std::span<const Point3> points,
                                 std::vector<Point3>& scratch,
                                 std::vector<std::pair<std::uint32_t, std::uint32_t>>& bad);
// Number of invalid cells (exact), parallel.
std::size_t count_invalid_cells(const MeshStencil& s, std::span<const Point3> points);

}  // namespace polydual
