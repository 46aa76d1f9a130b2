// A local round of the split loop (split/split.h, pipeline/convert.cpp): after
// the vertices D are newly cut whole, only the cells of N[D] (D and its
// neighbours) can change (every point, face and side of a cell of w reads
// only the tets of star(w), and a tet of star(w) holds a vertex of D only if
// w is in N[D]; proofs/split.md, L5). Of those, the cells of vertices cut
// whole are barycentric corners, convex by construction (proofs/dual_cuts.md
// C5): whatever their verdict, their vertex cannot be cut further, so a
// round does not build or test them (the final whole build does, exactly).
// So the round builds the dual of the sub-mesh star(U), U = N[D] without the
// vertices cut whole (mesh/sub_mesh.h), with the faces of U's cells only
// (dual/build_dual.h, DualScope) and star-tests U's cells, instead of
// rebuilding and rechecking the whole dual. Its verdicts only choose which
// vertices the next round cuts: the mesh returned is one whole build, checked
// exactly (the caller's), so correctness never rests on a local round.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "core/json.h"
#include "dual/build_dual.h"
#include "dual/vertex_cuts.h"
#include "mesh/classified_tet_mesh.h"
#include "mesh/sub_mesh.h"

namespace polydual {

// The sub-mesh star(U), U = N[changed] without the vertices marked in
// `whole`, its active vertices (those of U)
// and its dual with the faces of the active vertices' cells only, built with
// the whole mesh's cuts restricted to it: the free-edge cuts of every vertex
// (the triangles with both tets in the sub-mesh) and the whole cuts of the
// vertices marked in `whole` (per vertex of m). collapse_length: the whole
// mesh's (dual_collapse_length), so the sub-mesh collapses what the whole mesh
// does. When star(U) holds more than whole_mesh_share of m's tets,
// m itself is used (no copy; the same scope and cuts): a copy of most of the
// mesh costs more than it saves. Either way the k-th cell of an active vertex
// is the k-th cell of that vertex in the whole mesh's dual (proofs/split.md
// L5; tests/split/split_local_round_test.cpp).
struct LocalDual {
  SubMesh sub;               // empty when on_whole_mesh
  bool on_whole_mesh = false;
  std::vector<char> active;  // per vertex of the mesh the dual is of
  PolyMesh dual;
  Json seconds = Json::object();  // sub_mesh, cuts, dual (wall)

  // The mesh the dual is of (m or sub.mesh), and its vertex v in m's numbering.
  const ClassifiedTetMesh& mesh(const ClassifiedTetMesh& m) const { return on_whole_mesh ? m : sub.mesh; }
  VertexId whole_vertex(std::size_t v) const { return on_whole_mesh ? VertexId(v) : sub.vertex[v]; }
};
constexpr double kWholeMeshShare = 0.5;

// `cuts` (m's numbering) restricted to the sub-mesh s: the cut triangles
// with both tets in it, and the whole flags of its vertices.
VertexCuts restrict_cuts(const ClassifiedTetMesh& m, const SubMesh& s, const VertexCuts& cuts);

LocalDual local_dual(const ClassifiedTetMesh& m, const VertexCuts& free_edge, std::span<const char> whole,
                     std::span<const VertexId> changed, const DualParams& params, double collapse_length,
                     double whole_mesh_share = kWholeMeshShare);

struct LocalRound {
  std::vector<VertexId> vertices;      // U = N[D] without the whole vertices, increasing (the whole mesh's numbering)
  std::vector<std::uint32_t> invalid;  // per vertex of U, its cells the star test found invalid
  std::size_t tets = 0;                // of the mesh the dual is of
  bool on_whole_mesh = false;
  std::size_t cells_tested = 0;
  Json seconds = Json::object();       // local_dual's, and star_test (wall)
};

// local_dual, then the exact star test of the active vertices' cells.
LocalRound local_round(const ClassifiedTetMesh& m, const VertexCuts& free_edge, std::span<const char> whole,
                       std::span<const VertexId> changed, const DualParams& params, double collapse_length,
                       double whole_mesh_share = kWholeMeshShare);

}  // namespace polydual
