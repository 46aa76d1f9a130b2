// What virtual cut surfaces (dual/vertex_cuts.h, design §8) change in
// Algorithm 1, decided once per mesh before the dual is built:
//  - which triangles are cut by which of their vertices (they get a centre);
//  - which edges are stop edges (they get a midpoint, every fan face of the
//    edge passes through it and the caps at both ends stop there);
//  - which vertices get a point although they are no model vertex.
// The rules and why they close every cell: proofs/dual_cuts.md.
#pragma once
#include <cstdint>
#include <vector>

#include "dual/vertex_cuts.h"
#include "mesh/classified_tet_mesh.h"
#include "mesh/poly_mesh.h"

namespace polydual {

struct CutTopology {
  // False: no cuts (null or empty); every other member is then empty and
  // Algorithm 1 runs exactly as without cuts.
  bool active = false;
  const VertexCuts* cuts = nullptr;
  // Per triangle: bit i set iff triangle(f)[i] cuts f (f is in its cut set);
  // kCentre: f is an interior triangle through a whole vertex, which keeps
  // its centre whether or not it cuts (cut_by reads bits 0-2 only).
  static constexpr std::uint8_t kCentre = 8;
  std::vector<std::uint8_t> tri_mask;
  // Per edge, bits: kStop, stop(e) (model edge, or the cut sets of its ends
  // disagree on its ring: proofs/dual_cuts.md, rule S); kRingCut, some
  // triangle of its ring is cut (an edge in a region without it keeps
  // Algorithm 1's closed face of tet centres). One byte for both: with a
  // second per-edge array the peak of `convert --optimize none` on a 1M-tet
  // cube was 719 MB against 678 (measured; the cause is not understood).
  static constexpr std::uint8_t kStop = 1, kRingCut = 2;
  std::vector<std::uint8_t> edge_bits;
  // Per vertex: v gets a dual point (model vertex, or >= 3 stop edges on
  // which a cap of v ends).
  std::vector<char> vertex_point;

  bool is_cut(TriId f) const { return active && tri_mask[f.idx] != 0; }
  bool stop(EdgeId e) const { return active && (edge_bits[e.idx] & kStop) != 0; }
  bool ring_cut(EdgeId e) const { return active && (edge_bits[e.idx] & kRingCut) != 0; }
  // Whether v (a vertex of f) cuts f, from tri_mask (no search of v's cut
  // list; cut_topology() fills the mask before any use).
  bool cut_by(const ClassifiedTetMesh& m, TriId f, VertexId v) const {
    if (!active) return false;
    const unsigned mask = tri_mask[f.idx];
    if (mask == 0) return false;
    const auto t = m.triangle(f);
    return (mask & (unsigned(t[0] == v) | unsigned(t[1] == v) << 1 | unsigned(t[2] == v) << 2)) != 0;
  }
  // Whether f ends the fans of v's edges, as a triangle that v cuts does:
  // cut by v, or an interior triangle through v when v is whole (kCentre).
  // A whole vertex's fan faces are therefore the same whichever of its
  // triangles cut it, and so are its neighbours' cells (split/coarsen.h).
  bool position_for(const ClassifiedTetMesh& m, TriId f, VertexId v) const {
    return cut_by(m, f, v) || (active && (tri_mask[f.idx] & kCentre) != 0 && cuts->is_whole(v));
  }
};

// Whether the point made from primal entity o (PolyMesh::point_origin) is
// pinned by a whole-cut vertex (VertexCuts::whole): o has such a vertex. A
// pinned point sits at barycentre(m, o) and is never merged or collapsed.
bool pinned(const ClassifiedTetMesh& m, const VertexCuts* cuts, PointOrigin o);
// The barycentre of primal entity o: the vertex, the edge's midpoint, the
// triangle's centroid as a + (b-a)/3 + (c-a)/3 (exactly in an axis-aligned
// plane of the triangle), the tet's centroid.
Point3 barycentre(const ClassifiedTetMesh& m, PointOrigin o);

// Checks the cut sets against the mesh (sizes, increasing ids, each triangle
// through its vertex and on no model face): InputError naming the mesh's
// source, the vertex (input numbering) and the triangle otherwise.
CutTopology cut_topology(const ClassifiedTetMesh& mesh, const VertexCuts* cuts);

// A triangle of edge e = (a, b)'s ring cuts the ring (a position: the fan
// faces of e end there) iff it is on a model face or a position for a or b
// (in cut(a) or cut(b), or interior through a whole a or b).
inline bool ring_position(const ClassifiedTetMesh& m, const CutTopology& ct, TriId f, VertexId a, VertexId b) {
  return m.on_model_face(f) || ct.position_for(m, f, a) || ct.position_for(m, f, b);
}

}  // namespace polydual
