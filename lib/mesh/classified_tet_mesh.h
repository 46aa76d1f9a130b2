// The classified tetrahedral mesh every later stage reads (design §1, §3).
// Built by classify() from a TetSoup; immutable afterwards.
//
// Conventions:
//  - every tet (v0,v1,v2,v3) is positively oriented: det[v1-v0, v2-v0, v3-v0] > 0
//    (checked exactly on load);
//  - local face i of a tet is the triangle opposite its local vertex i;
//  - local edge k of a tet joins kTetEdge[k][0] and kTetEdge[k][1].
#pragma once
#include <algorithm>
#include <array>
#include <climits>
#include <bit>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/bits.h"
#include "core/classification.h"
#include "core/handles.h"
#include "core/vec3.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace polydual {

inline constexpr int kTetEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
// Local face i (opposite local vertex i) of a positive tet, ordered so that its
// right-hand normal points out of the tet.
inline constexpr int kTetFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

namespace detail {
// For local indices ia, ib of an edge, the other two local indices (c, d) such
// that (ia, ib, c, d) is an even permutation: going around ia->ib right-handedly
// inside the tet leads from c to d. Tabulated: this sits in the edge-ring walks.
struct RingTable {
  std::int8_t c[4][4], d[4][4];
  constexpr RingTable() : c{}, d{} {
    for (int ia = 0; ia < 4; ++ia)
      for (int ib = 0; ib < 4; ++ib) {
        if (ia == ib) continue;
        int o[2] = {0, 0}, n = 0;
        for (int i = 0; i < 4; ++i)
          if (i != ia && i != ib) o[n++] = i;
        int p[4] = {ia, ib, o[0], o[1]}, inv = 0;
        for (int i = 0; i < 4; ++i)
          for (int j = i + 1; j < 4; ++j) inv += p[i] > p[j];
        const bool even = inv % 2 == 0;
        c[ia][ib] = static_cast<std::int8_t>(even ? o[0] : o[1]);
        d[ia][ib] = static_cast<std::int8_t>(even ? o[1] : o[0]);
      }
  }
};
inline constexpr RingTable kRing;
// The local edge joining local vertices i != j (kTetEdge's inverse).
inline constexpr auto kEdgeOf = [] {
  std::array<std::array<std::int8_t, 4>, 4> e{};
  for (int k = 0; k < 6; ++k) {
    e[kTetEdge[k][0]][kTetEdge[k][1]] = std::int8_t(k);
    e[kTetEdge[k][1]][kTetEdge[k][0]] = std::int8_t(k);
  }
  return e;
}();
}  // namespace detail

// One entity of the geometric model and the higher-dimensional entities it bounds
// (a model face lists its regions: 0 for a fracture inside one region, 1 external,
// 2 interface; a model edge lists its faces; a model vertex its edges).
//
// Provenance: `source_tag` is the tag the file gave this entity's elements
// (a region tag; a Gmsh surface / curve / point entity; a face marker of
// TetGen .face, Medit triangle refs, Gmsh 2.2 physicals, VTU cell data),
// std::nullopt when the entity was inferred. One file tag can give several
// model entities: a marker split at sharp edges (the feature angle) or
// spanning disconnected parts gives model faces of different `tag`s sharing
// one `source_tag` (the marker is their group, e.g. an OpenFOAM patch).
// `name` is the name of the first named group of the soup (TetSoup::groups,
// in (dim, tag) order) of the same dimension that lists `source_tag`, "" when
// none does; `groups` are the tags of all those groups.
struct ModelEntity {
  int dim = 0;
  std::int32_t tag = 0;
  std::vector<std::int32_t> bounds;  // tags of dimension dim+1, sorted, unique
  std::vector<std::int32_t> regions; // for faces: regions on its sides (1 or 2 tags, equal twice for a fracture)
  std::optional<std::int32_t> source_tag;
  std::string name;
  // The tags of every physical group (TetSoup::groups) of this dimension that
  // lists `source_tag`, increasing: all of a Gmsh entity's physical tags.
  std::vector<std::int32_t> groups;
  // Faces: all its triangles lie in one plane (decided by classify() with the
  // exact orientation test; data structures decide no signs). False when
  // unknown or curved.
  bool planar = false;
};

// The kind of a model face (dim 2) from its regions: one region listed ->
// External; two equal -> Fracture (the same region on both sides); two
// different -> Interface. The one place this rule is written.
FaceKind face_kind(const ModelEntity& face);

struct ModelTopology {
  std::array<std::vector<ModelEntity>, 4> entities;  // by dimension, sorted by tag
  const ModelEntity* find(int dim, std::int32_t tag) const;
  std::size_t count(int dim) const { return entities[dim].size(); }
  // face_kind() of the model face `tag`; a tag that names no model face is a
  // caller's error (std::out_of_range naming the tag).
  FaceKind face_kind(std::int32_t tag) const;
};

// What classify() made of one face marker of the file (a surface tag of
// TetGen .face, Medit refs, Gmsh 2.2 physicals, VTU cell data), or of the
// boundary and interface triangles the file tagged with none, and why: the
// edges inside it that bend above the feature angle, which of them were kept
// as features (classify/features.h) and which dropped as the facets of a
// curved surface, and the model entities that resulted.
struct MarkerFeatures {
  std::optional<std::int32_t> marker;  // none: the untagged triangles
  std::size_t facets = 0;              // model-face triangles
  std::size_t model_faces = 0;         // model faces made from them
  std::size_t model_edges = 0;         // model edges along those faces
  std::size_t corners = 0;             // model vertices on those faces
  std::size_t sharp_edges = 0;         // bending above the feature angle inside the marker
  std::size_t strong_edges = 0;        // kept: above the strong angle
  std::size_t chain_edges = 0;         // kept: in a feature line (a chain of consistently sharp edges)
  std::size_t noise_edges = 0;         // dropped: isolated, zigzag or short loose chains
};

class ClassifiedTetMesh {
 public:
  // --- sizes
  std::size_t num_vertices() const { return points_.size(); }
  std::size_t num_tets() const { return tets_.size(); }
  std::size_t num_triangles() const { return tri_code_.size(); }
  std::size_t num_edges() const { return edge_code_.size(); }

  // --- geometry and connectivity
  const std::string& source() const { return source_; }
  const Point3& point(VertexId v) const { return points_[v.idx]; }
  const std::vector<Point3>& points() const { return points_; }
  const std::array<VertexId, 4>& tet(TetId t) const { return tets_[t.idx]; }
  std::int32_t region(TetId t) const { return tet_region_[t.idx]; }
  // Neighbour across local face i (invalid on the boundary).
  TetId tet_neighbor(TetId t, int i) const {
    const std::uint32_t c = tet_adj_[4 * t.idx + i];
    return TetId((c >> 2) | (0u - std::uint32_t(c == kNoNeighbour)));  // invalid() is all ones
  }
  // The neighbour's local index of the shared face (-1 on the boundary).
  int tet_neighbor_face(TetId t, int i) const {
    const std::uint32_t c = tet_adj_[4 * t.idx + i];
    return c == kNoNeighbour ? -1 : int(c & 3u);
  }
  // The triangle on local face i: the rank of the face's first occurrence
  // (its own code, or its neighbour's if that is smaller) among first ones.
  TriId tet_triangle(TetId t, int i) const {
    const std::uint32_t c = 4 * t.idx + std::uint32_t(i), first = std::min(c, tet_adj_[c]);
    const std::uint64_t below = tri_first_bits_[first >> 6] & ((std::uint64_t(1) << (first & 63)) - 1);
    return TriId(tri_first_rank_[first >> 6] + std::uint32_t(popcount64(below)));
  }
  EdgeId tet_edge(TetId t, int k) const { return tet_edge_[6 * t.idx + k]; }
  // The triangle's vertices, oriented so its right-hand normal points out of
  // triangle_tet(f, 0).
  std::array<VertexId, 3> triangle(TriId f) const {
    const std::uint32_t c = tri_code_[f.idx];
    const auto& tv = tets_[c >> 2];
    const int* o = kTetFace[c & 3];
    return {tv[o[0]], tv[o[1]], tv[o[2]]};
  }
  // The one or two tets of a triangle (side 1 invalid on the boundary).
  TetId triangle_tet(TriId f, int side) const {
    const std::uint32_t c = tri_code_[f.idx];
    if (side == 0) return TetId(c >> 2);
    const std::uint32_t a = tet_adj_[c];
    return a == kNoNeighbour ? TetId::invalid() : TetId(a >> 2);
  }
  // The edge's vertices (a, b), a < b.
  std::array<VertexId, 2> edge(EdgeId e) const {
    const std::uint32_t c = edge_code_[e.idx];
    const auto& tv = tets_[c >> 3];
    const VertexId p = tv[kTetEdge[c & 7][0]], q = tv[kTetEdge[c & 7][1]];
    return p < q ? std::array<VertexId, 2>{p, q} : std::array<VertexId, 2>{q, p};
  }
  // One tet that has edge e.
  TetId edge_tet(EdgeId e) const { return TetId(edge_code_[e.idx] >> 3); }
  // Tets around a vertex (its star), in increasing tet order.
  std::span<const TetId> vertex_tets(VertexId v) const {
    return {vstar_.data() + vstar_off_[v.idx], vstar_.data() + vstar_off_[v.idx + 1]};
  }
  // Position of tet t in vertex_tets(v) (t must have v). A branch-free binary
  // search: the halving steps depend on the star's size only.
  std::uint32_t star_rank(VertexId v, TetId t) const {
    const TetId* base = vstar_.data() + vstar_off_[v.idx];
    const TetId* first = base;
    std::uint32_t len = vstar_off_[v.idx + 1] - vstar_off_[v.idx];
    while (len > 1) {
      const std::uint32_t half = len / 2;
      base += half & (0u - std::uint32_t(base[half - 1].idx < t.idx));  // a mask, not a branch
      len -= half;
    }
    return std::uint32_t(base - first) + std::uint32_t(base->idx < t.idx);
  }
  // The tets around edge e in right-handed order about edge(e)[0] -> edge(e)[1].
  // For an edge on the boundary the ring is open and starts at a tet whose
  // predecessor does not exist; `closed` tells which. This is the chain of
  // edge_tet(e) only (see for_each_edge_chain for the others).
  std::vector<TetId> edge_ring(EdgeId e, bool* closed = nullptr) const;
  // The ring with the triangles between its tets: tris.size() == tets.size()+1,
  // tris[k] precedes tets[k] and tris[k+1] follows it in the right-handed order;
  // for a closed ring tris.front() == tris.back().
  void edge_ring(EdgeId e, std::vector<TetId>& tets, std::vector<TriId>& tris, bool& closed) const {
    edge_ring_from(e, edge_tet(e), tets, tris, closed);
  }
  // The same for the chain of tet `start` (which must have edge e).
  void edge_ring_from(EdgeId e, TetId start, std::vector<TetId>& tets, std::vector<TriId>& tris,
                      bool& closed) const;

  // --- chains (proofs/edge_chains.md). The tets around an edge, joined across
  // the triangles through it, fall into chains: one closed chain inside the
  // mesh, one open chain on a manifold boundary, and one open chain per pass
  // of the outside where the mesh touches itself along the edge (two tets
  // sharing only that edge; three materials and the outside meeting there).
  // Each open chain starts and ends on a boundary triangle, so an edge has
  // several chains iff more than two boundary triangles meet at it (in a mesh
  // whose tets do not overlap: a closed chain winds once round the edge and
  // leaves room for no other).
  // Edges with several chains, increasing (usually none).
  std::span<const EdgeId> multi_chain_edges() const { return multi_chain_edges_; }
  bool has_several_chains(EdgeId e) const {
    return !multi_chain_edges_.empty() &&
           std::binary_search(multi_chain_edges_.begin(), multi_chain_edges_.end(), e,
                              [](EdgeId x, EdgeId y) { return x.idx < y.idx; });
  }
  // Calls f(closed) once per chain of e with tets and tris holding it as
  // edge_ring() does: first the chain of edge_tet(e) (edge_ring() itself),
  // then the others in the order of their first tet in vertex_tets(edge(e)[0]).
  // Every tet around e is in exactly one call. f must not keep the vectors.
  template <class F>
  void for_each_edge_chain(EdgeId e, std::vector<TetId>& tets, std::vector<TriId>& tris, F&& f) const {
    bool closed;
    edge_ring(e, tets, tris, closed);
    if (closed || !has_several_chains(e)) {
      f(closed);
      return;
    }
    const std::vector<TetId> starts = other_chain_starts(e, tets);
    f(closed);
    for (TetId s : starts) {
      edge_ring_from(e, s, tets, tris, closed);
      f(closed);
    }
  }
  // One tet of each chain of e other than `first` (a chain of e), in the
  // order of for_each_edge_chain.
  std::vector<TetId> other_chain_starts(EdgeId e, std::span<const TetId> first) const;
  // Calls f(t) for each tet around an edge whose ring is closed (an edge
  // classified in a region is), in edge_ring's order, without building the ring.
  template <class F>
  void for_each_closed_ring_tet(EdgeId e, F&& f) const {
    const auto [a, b] = edge(e);
    const TetId start = edge_tet(e);
    TetId t = start;
    do {
      f(t);
      const std::uint32_t code = tet_adj_[4 * t.idx + detail::kRing.c[local_index(t, a)][local_index(t, b)]];
      if (code == kNoNeighbour) return;  // open after all: the caller broke the contract
      t = TetId(code >> 2);
    } while (t != start);
  }
  // The edge joining two distinct vertices a, b of triangle f (a precondition).
  EdgeId triangle_edge(TriId f, VertexId a, VertexId b) const {
    const TetId t = triangle_tet(f, 0);
    return tet_edge(t, detail::kEdgeOf[local_index(t, a)][local_index(t, b)]);
  }
  // Local index (0..3) of v in tet t, or -1. Branch-free where SSE2 is there:
  // the edge-ring walks call it twice per step, and which slot holds v is
  // as good as random to a branch predictor.
  int local_index(TetId t, VertexId v) const {
#if defined(__SSE2__)
    static_assert(sizeof(std::array<VertexId, 4>) == 16);
    const __m128i tv = _mm_loadu_si128(reinterpret_cast<const __m128i*>(tets_[t.idx].data()));
    const unsigned m = unsigned(_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(tv, _mm_set1_epi32(int(v.idx)))))) | 16u;
    const int i = std::countr_zero(m);
    return i == 4 ? -1 : i;
#else
    const auto& tv = tets_[t.idx];
    return tv[0] == v ? 0 : tv[1] == v ? 1 : tv[2] == v ? 2 : tv[3] == v ? 3 : -1;
#endif
  }
  // Edge id of the edge (a,b), or invalid if a and b share no tet.
  EdgeId find_edge(VertexId a, VertexId b) const;

  // --- numbering of the input (classify() renumbers spatially, lib/classify/spatial_order.h)
  // The input file's 0-based index of vertex v / tet t.
  std::uint32_t input_vertex(VertexId v) const { return input_vertex_[v.idx]; }
  std::uint32_t input_tet(TetId t) const { return input_tet_[t.idx]; }
  const std::vector<std::uint32_t>& input_vertices() const { return input_vertex_; }

  // --- classification
  ModelRef vertex_class(VertexId v) const { return vertex_class_[v.idx]; }
  ModelRef edge_class(EdgeId e) const { return edge_class_[e.idx]; }
  // A triangle is on a model face (dim 2) or on none (unclassified).
  ModelRef triangle_class(TriId f) const {
    const std::int32_t tag = tri_face_[f.idx];
    return tag == kNoFace ? ModelRef{} : ModelRef{2, tag};
  }
  bool on_model_face(TriId f) const { return tri_face_[f.idx] != kNoFace; }
  const ModelTopology& model() const { return model_; }
  // What classify() completed or changed in a classification the file gave
  // as complete (TetSoup::full_classification): one line each, starting with
  // the file name, for the command to print. Empty otherwise.
  const std::vector<std::string>& classification_warnings() const { return warnings_; }
  // Per face marker (untagged first, then by marker): what classify() split
  // and why. Empty for a full classification (its surfaces are not split).
  const std::vector<MarkerFeatures>& marker_features() const { return marker_features_; }

  // The one change a classified mesh allows: the same mesh (tets, numbering,
  // topology, classification) at new coordinates, one per vertex (the tet
  // pre-optimiser's, optim/tet_optimize.h). The topology does not read the
  // coordinates, so it is copied, not rebuilt. Whether every tet is still
  // positively oriented is the caller's exact check. Throws UsageError when
  // points.size() is not num_vertices().
  ClassifiedTetMesh with_points(std::vector<Point3> points) const;

  // Volume of tet t (double; for statistics only).
  double tet_volume(TetId t) const;

 private:
  friend class TetMeshBuilder;
  std::string source_;
  std::vector<Point3> points_;
  std::vector<std::array<VertexId, 4>> tets_;
  std::vector<std::int32_t> tet_region_;
  std::vector<std::uint32_t> input_vertex_, input_tet_;
  static constexpr std::uint32_t kNoNeighbour = 0xffffffffu;
  std::vector<std::uint32_t> tet_adj_;  // 4 per tet: 4 * neighbour + its local face, or kNoNeighbour
  // Local faces that are a triangle's first (4 t + i order): one bit each,
  // and the number of first faces before each 64-bit word.
  std::vector<std::uint64_t> tri_first_bits_;
  std::vector<std::uint32_t> tri_first_rank_;
  std::vector<EdgeId> tet_edge_; // 6 per tet
  // Triangles and edges are stored as one local entity of one of their tets:
  // 4 * tet + local face (the triangle's first tet, which it points out of)
  // and 8 * tet + local edge.
  std::vector<std::uint32_t> tri_code_;
  std::vector<std::uint32_t> edge_code_;
  std::vector<std::uint32_t> vstar_off_;
  std::vector<TetId> vstar_;
  std::vector<EdgeId> multi_chain_edges_;  // increasing
  std::vector<ModelRef> vertex_class_, edge_class_;
  // Per triangle: the tag of its model face, or kNoFace (4 bytes, not a
  // ModelRef's 8: triangles are only ever on a model face or on none).
  static constexpr std::int32_t kNoFace = INT32_MIN;
  std::vector<std::int32_t> tri_face_;
  ModelTopology model_;
  std::vector<std::string> warnings_;
  std::vector<MarkerFeatures> marker_features_;
};

// Builds the connectivity of a ClassifiedTetMesh (adjacency, triangles, edges,
// stars). Used by classify(); exposes the setters classification needs.
class TetMeshBuilder {
 public:
  // Throws InputError (naming `source` and the tet) on non-conformity: a
  // triangle shared by more than two tets. input_vertex/input_tet map the ids
  // to the input's numbering (for error messages and outputs); empty = identity.
  static ClassifiedTetMesh build_topology(std::string source, std::vector<Point3> points,
                                          std::vector<std::array<VertexId, 4>> tets,
                                          std::vector<std::int32_t> regions,
                                          std::vector<std::uint32_t> input_vertex = {},
                                          std::vector<std::uint32_t> input_tet = {});
  static std::vector<ModelRef>& vertex_class(ClassifiedTetMesh& m) { return m.vertex_class_; }
  static std::vector<ModelRef>& edge_class(ClassifiedTetMesh& m) { return m.edge_class_; }
  // Model-face tag per triangle, ClassifiedTetMesh::kNoFace where none.
  static std::vector<std::int32_t>& triangle_face(ClassifiedTetMesh& m) { return m.tri_face_; }
  static constexpr std::int32_t kNoFace = ClassifiedTetMesh::kNoFace;
  static ModelTopology& model(ClassifiedTetMesh& m) { return m.model_; }
  static std::vector<std::string>& classification_warnings(ClassifiedTetMesh& m) { return m.warnings_; }
  static std::vector<MarkerFeatures>& marker_features(ClassifiedTetMesh& m) { return m.marker_features_; }

 private:
  // build_topology()'s phases, in order (lib/mesh/classified_tet_mesh.cpp).
  struct LowVertexBuckets;
  static void build_vertex_stars(ClassifiedTetMesh& m);
  static LowVertexBuckets bucket_by_low_vertices(const ClassifiedTetMesh& m);
  static std::size_t match_faces(ClassifiedTetMesh& m, const LowVertexBuckets& b);
  static void check_opposite_sides(const ClassifiedTetMesh& m, const LowVertexBuckets& b);
  static void number_triangles(ClassifiedTetMesh& m, std::size_t num_tris);
  static void number_edges(ClassifiedTetMesh& m, const LowVertexBuckets& b, std::size_t num_tris);
  static void find_multi_chain_edges(ClassifiedTetMesh& m);
};

// The inverse of input_vertex: per input vertex index, the internal vertex
// (invalid: an input point that is in no tet).
std::vector<VertexId> internal_of_input(const ClassifiedTetMesh& m);

}  // namespace polydual
