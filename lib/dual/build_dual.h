// The dual mesh (design §4, paper Algorithm 1): one polyhedral cell per side of
// every primal vertex, conformal across interfaces and fractures, with every
// model vertex, edge and face represented.
//
// Three stages, composed by build_dual():
//   build_dual_draft()  steps 1-7: points, fan faces, caps, and the hints of
//                       the cleanup (exact coincidences, short tet-centre edges);
//   cleanup_dual()      step 9 (lib/dual/cleanup.h): merge, collapse, compact;
//   assemble_cells()    step 8: each cell's half-faces from the face owners.
#pragma once
#include <cstdint>
#include <span>
#include <string_view>

#include "core/json.h"
#include "dual/cleanup.h"
#include "dual/dual_draft.h"
#include "dual/vertex_cuts.h"
#include "mesh/classified_tet_mesh.h"
#include "mesh/poly_mesh.h"

namespace polydual {

// What the dual's boundary is (design §4.10).
//   Caps: the paper's capping faces (IMR 2013 §2.7): around a boundary vertex v
//     the cap joins the centres of v's model-face triangles (and the midpoints
//     of its model edges, v itself at a model vertex); on a curved model face
//     it cuts the corner at v, so a convex body loses volume.
//   Keep: the dual's boundary is the primal's boundary triangulation. Every
//     vertex on a model face, edge or vertex, and the midpoint of every edge
//     on one, is a dual point; each model-face triangle t is tiled by the three
//     planar quads (v_i, mid(v_i v_j), centre(t), mid(v_i v_k)), the quads
//     around v merged where their triangles are exactly coplanar. The sum of
//     the cells' volumes per material is then the primal's
//     (proofs/dual_invariants.md L5).
enum class BoundaryMode : std::uint8_t { Keep, Caps };
const char* boundary_mode_name(BoundaryMode m);  // "keep" | "caps"
BoundaryMode parse_boundary_mode(std::string_view s);  // UsageError on anything else

struct DualParams {
  // The dual's boundary (BoundaryMode above).
  BoundaryMode boundary = BoundaryMode::Caps;
  // Run the cleanup (design §4.9): exact merge of coincident dual points, then
  // collapse of short edges. Off: build_dual_draft() finds no hints and
  // build_dual() skips cleanup_dual().
  bool cleanup = true;
  // Edges shorter than collapse_tolerance x (mean primal edge length) are
  // collapsed (only between points of the same classification). Relative
  // (no unit); 0 disables the collapse (the exact merge still runs). At most
  // half an edge: a larger tolerance would collapse the dual's own edges,
  // whose lengths are a fraction of the primal's.
  double collapse_tolerance = 1e-3;
  static constexpr double kMinCollapseTolerance = 0.0;
  static constexpr double kMaxCollapseTolerance = 0.5;

  // Throws UsageError naming the field, its unit and its allowed range.
  void validate() const;
  Json to_json() const;
};

struct DualStats {
  std::size_t well_centred_tets = 0, clamped_tets = 0;
  std::size_t well_centred_triangles = 0, clamped_triangles = 0;
  std::size_t merged_points = 0;      // by the exact cospherical merge
  std::size_t collapsed_points = 0;   // by the short-edge collapse
  std::size_t dropped_faces = 0;      // faces that degenerated below 3 points
  std::size_t slit_faces = 0;         // owner == neighbour (fracture tips)
  // Wall-clock seconds: points (steps 1-4), sides, faces (5-7), hints (the
  // exact coincidences and short tet-centre edges, found by the draft),
  // cleanup (step 9), cells (step 8).
  double seconds_points = 0, seconds_sides = 0, seconds_faces = 0, seconds_hints = 0, seconds_cleanup = 0,
         seconds_cells = 0;
  Json to_json() const;
};

// The dual of part of a mesh (the split's local rounds, split/local_round.h).
// Only the faces of the cells of the active vertices are built: the fan faces
// of the edges with an active end and the caps of the active vertices. The
// cells of an active vertex v are then those of the whole mesh's dual when
// the mesh is a sub-mesh (mesh/sub_mesh.h) holding every tet of star(v):
// every ring and cap they read is complete (proofs/split.md L5, up to a
// clean-up chain leaving the sub-mesh); the other cells are partial and
// meaningless. A sub-mesh boundary that is not a model boundary is safe: no
// built face reads a triangle outside the active vertices' stars.
struct DualScope {
  std::span<const char> active;  // per vertex of the mesh; empty: all vertices
  // Absolute collapse length (the whole mesh's tolerance x mean edge, so a
  // sub-mesh collapses what the whole mesh does); < 0: from DualParams.
  double collapse_length = -1;
};

// Steps 1-7 and the cleanup's hints (when params.cleanup). Fills the stats of
// these steps (counts of well-centred/clamped simplices, slit faces, seconds
// of points, sides, faces and hints); leaves the cleanup's and cells' alone.
// Throws UsageError if params do not validate().
//
// cuts (dual/vertex_cuts.h, design §8; null or empty: none, and the result
// is the same as without the argument): each vertex v gets one cell per side
// of its star cut by the model faces and cut(v); cut triangles get centres
// (classified in their region), the edges where the cut sets of the two ends
// disagree get midpoints, and the faces of the neighbouring cells pass
// through them so every cell stays closed (the rules: proofs/dual_cuts.md).
// Bad cut sets (not through their vertex, on a model face, not increasing,
// sizes wrong) throw InputError naming the mesh's source and the vertex.
// Every point's primal entity is in mesh.point_origin (internal numbering).
// scope (null: the whole mesh, as without it): see DualScope; its active
// flags, when given, are one per vertex of mesh (else UsageError).
DualDraft build_dual_draft(const ClassifiedTetMesh& mesh, const DualParams& params = {},
                           DualStats* stats = nullptr, const VertexCuts* cuts = nullptr,
                           const DualScope* scope = nullptr);

// The absolute length below which the cleanup collapses a dual edge:
// params.collapse_tolerance x the mean primal edge length of m.
double dual_collapse_length(const ClassifiedTetMesh& m, const DualParams& params);

// Step 8: the cells' half-face lists (face order within a cell), from the face
// owners and neighbours. Consumes the draft (hints, if any, are ignored).
PolyMesh assemble_cells(DualDraft&& draft);

// build_dual_draft, then cleanup_dual (when params.cleanup), then
// assemble_cells; *stats gets every stage's figures.
PolyMesh build_dual(const ClassifiedTetMesh& mesh, const DualParams& params = {},
                    DualStats* stats = nullptr, const VertexCuts* cuts = nullptr,
                    const DualScope* scope = nullptr);

}  // namespace polydual
