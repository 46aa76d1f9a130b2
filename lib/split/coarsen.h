// Coarsening of whole cuts (design §8, "split as little as possible";
// proofs/split.md L6). A vertex cut whole has one cell per tet of its star,
// the barycentric corners: certain, but many cells. Once the split has a
// valid mesh, adjacent corners of each whole vertex are merged back, in
// passes, while the exact star test keeps every cell valid:
//  - a vertex's cells are the classes of a label per tet of its star; it is
//    cut exactly where two tets sharing an interior triangle through it have
//    different labels (with the free-edge cuts kept), and it stays marked
//    whole, so every point of its cells is still pinned at the barycentre of
//    its primal entity (dual/vertex_cuts.h);
//  - a pass proposes, per whole vertex, a matching of its adjacent classes
//    (deterministic: by class representative) and merges the pairs;
//  - the caller's evaluator rebuilds the dual with the proposed cuts and
//    reports, exactly, which cells are invalid; a proposing vertex with an
//    invalid cell first takes back only the merges that made that cell (and
//    never proposes them again), then, if a cell of it is still invalid, all
//    of the pass's merges, as does a proposing vertex next to a vertex with
//    an invalid cell; the evaluation repeats until no cell is invalid
//    (reverting every proposer gives back the valid cuts the pass started
//    from).
// A vertex whose proposal was wholly reverted proposes half as many merges
// in the next pass and stops after kMaxFailures such reverts.
// The passes start from the corners, or (CoarsenStart::TopDown) from the
// first valid trial of a descent from the other end: every whole vertex one
// cell per side, then, while a trial has failing cells, the class of each
// bisected by a plane through its vertex. Only a vertex's own classes make
// its cells (proofs/split.md L6, Claim 1), so a failing cell is always a
// class of several tets, and the descent ends, at worst at the corners.
#pragma once
#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "core/json.h"
#include "dual/vertex_cuts.h"
#include "mesh/classified_tet_mesh.h"
#include "mesh/poly_mesh.h"
#include "quality/metrics.h"
#include "split/split.h"

namespace polydual {

struct CoarsenStats {
  std::size_t passes = 0;
  std::size_t evaluations = 0;
  std::size_t merges_proposed = 0;
  std::size_t merges_kept = 0;
  std::size_t reverts = 0;  // vertex proposals reverted
  std::size_t bisections = 0;  // classes of the top-down start bisected
  Json to_json() const;
};

// A cell found invalid: its primal vertex (m's numbering) and its rank among
// that vertex's cells (the side, dual/sides.h: by first tet in star order).
struct BadCell {
  VertexId v;
  std::uint32_t side;
};
// Given cuts, the cells of the dual built with those cuts that fail: found
// invalid by the exact star test (or rejected by the caller's other
// criteria, such as a quality bound).
using CutsEvaluator = std::function<std::vector<BadCell>(const VertexCuts&)>;

constexpr int kCoarsenMaxPasses = 32;
// A merged cell above this kappa/3 (and above the worst corner of its vertex)
// is taken back like an invalid one: the worst-cell target the optimiser
// reports against (OptimReport::cells_above_bound).
constexpr double kMergeQualityBound = 10.0;
constexpr int kMaxFailures = 4;

// Where the passes start (above). TopDown serves the dual without an
// optimiser: the merged cells stay where the pinned points put them, and it
// keeps 2.5-4x fewer cells over the uncut dual on TetGen and Gmsh meshes;
// with the optimiser, the merges from the corners let it reach a lower
// worst cell (a Gmsh multi-material model: kappa/3 15.7 against 23.8).
enum class CoarsenStart { Corners, TopDown };

// The coarsest cuts found: free_edge merged with the label cuts of the
// vertices marked in `whole` (kept whole). `evaluate(start)` must report no
// invalid cell for the cuts the coarsening starts from (with_whole_cuts of
// free_edge and whole); the result then has none either.
VertexCuts coarsen_whole_cuts(const ClassifiedTetMesh& m, const VertexCuts& free_edge, std::span<const char> whole,
                              const CutsEvaluator& evaluate, CoarsenStats* stats = nullptr,
                              int max_passes = kCoarsenMaxPasses, CoarsenStart start = CoarsenStart::Corners);

// The cuts of vertex v whose star tets (vertex_tets order) carry `label`:
// every interior triangle through v, on no model face, whose two tets have
// different labels, as (v, triangle) pairs appended to out.
void label_cuts(const ClassifiedTetMesh& m, VertexId v, std::span<const std::uint32_t> label,
                std::vector<std::pair<VertexId, TriId>>& out);

// Cell c's side among its primal vertex's cells (its rank: cells are
// numbered by vertex, then by side).
std::uint32_t cell_side(const PolyMesh& mesh, std::uint32_t c);

// `cuts` with the listed cells of whole vertices, as (vertex, side), split
// back into their barycentric corners: every interior triangle through the
// vertex in the side's tets cut (the coarsening's merges there undone).
VertexCuts split_back(const ClassifiedTetMesh& m, const VertexCuts& cuts, std::span<const BadCell> cells);

// Moves every point of `fresh` to the position of its partner in `old`, the
// partners being the k-th points (by index) of one primal origin in each
// mesh when the origin has as many points in both (a primal entity makes
// several points where it touches several sides: their order follows the
// builder's side order, the same in both meshes where the cuts near them
// agree); pinned points too. Returns fresh point -> old point (invalid: no
// partner), one-to-one, for split/recheck.h. A wrong pairing can only cost
// a merge: every trial is star-tested exactly.
std::vector<PointId> warm_start_by_rank(PolyMesh& fresh, const PolyMesh& old);

// The coarsening as a step of the split (split/split.h), on `mesh`, built
// with st.cuts and valid (check_base: its exact verdicts, every cell valid):
// trials rebuilt with build_dual(m, dual, .., trial cuts), every point where
// `mesh` has it, star-tested exactly; a merged cell above kMergeQualityBound
// and above its vertex's worst corner (cell_quality with `metric`) fails like
// an invalid one. Leaves the last valid trial in mesh, check_base (verdicts)
// and st.cuts; returns the step's record.
// With CoarsenStart::TopDown (no optimiser: every point where the build puts
// it) and `local`, a trial builds and star-tests only the cells of the
// whole vertices whose cuts changed since the last trial, on the sub-mesh of
// their stars (proofs/split.md L5, L6 Claim 1), and the cuts kept are built
// once at the end and checked exactly (should that build fail, the
// coarsening runs again with whole builds); `local` false: every trial a
// whole build, the reference the tests compare with.
Json coarsen_split(const ClassifiedTetMesh& m, const DualParams& dual, Metric metric, SplitState& st, PolyMesh& mesh,
                   CheckResult& check_base, CoarsenStart start = CoarsenStart::Corners, bool local = true);

}  // namespace polydual
