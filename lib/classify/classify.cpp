// Classification (design §3). The model entities are found bottom-up from the
// mesh: model-face triangles -> model faces (connected pieces, split by given
// tags, region pairs and feature edges — sharp edges in a feature line, not the
// facets of a coarse curved surface (classify/features.h) — which also split a
// given face marker unless the file gave a full classification); primal edges where the
// model-face triangles do not form one smooth manifold sheet -> model edges;
// vertices where model edges end, branch or bend -> model vertices. A full
// classification that lacks curves or points is completed the same way (fresh
// tags, warnings); one that contradicts itself is refused (proofs/
// classification.md L14). Every decision here is combinatorial except the
// feature tests (bends, turns, side normals: proofs/classification.md FE1),
// which are plain double geometry (an angle threshold is a modelling choice,
// not a sign that must be exact). Tet orientation and the planarity of model
// faces are decided exactly (lib/predicates).
#include "classify/classify.h"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <span>
#include <unordered_map>

#include "classify/features.h"
#include "classify/self_overlap.h"
#include "classify/spatial_order.h"
#include "core/union_find.h"
#include "core/radix_sort.h"
#include "core/error.h"
#include "core/param_range.h"
#include "predicates/predicates.h"

namespace polydual {

namespace {

constexpr std::int32_t kNoTag = std::numeric_limits<std::int32_t>::min();

std::string vlist(std::initializer_list<std::uint32_t> v) {
  std::string s = "(";
  bool first = true;
  for (auto x : v) { s += (first ? "" : ", ") + std::to_string(x + 1); first = false; }
  return s + ")";
}

// Validate indices and coordinates; drop unused vertices (remap everything).
// The validated input in spatial order (lib/classify/spatial_order.h).
struct Compacted {
  std::vector<Point3> points;
  std::vector<std::array<VertexId, 4>> tets;
  std::vector<std::int32_t> regions;
  std::vector<std::uint32_t> remap;         // soup vertex index -> vertex id (or -1)
  std::vector<std::uint32_t> input_vertex;  // vertex id -> soup vertex index
  std::vector<std::uint32_t> input_tet;     // tet id -> soup tet index
  std::size_t flipped = 0;                   // tets turned positive (all of them, or none)
};

// Indices in range, no repeated vertex in a tet, finite coordinates of the
// used vertices; returns which vertices are used.
// Coordinates the floating-point stages can take: finite, of magnitude at most
// kMaxCoordinate, spanning at least kMinExtent. The exact predicates take any
// double, but the dual's points (means, face normals) and the optimiser's
// kappa square and cube coordinate differences: 3.3e81 overflowed a normal to
// inf and the optimiser's primitive search to NaN (fuzz_pipeline).
constexpr double kMaxCoordinate = 1e30;
constexpr double kMinExtent = 1e-30;

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

void check_coordinates(const TetSoup& s, const std::vector<char>& used) {
  Point3 lo{kMaxCoordinate, kMaxCoordinate, kMaxCoordinate}, hi{-kMaxCoordinate, -kMaxCoordinate, -kMaxCoordinate};
  for (std::size_t v = 0; v < s.points.size(); ++v) {
    if (!used[v]) continue;
    const Point3& x = s.points[v];
    if (!is_finite(x)) throw InputError(s.source, "vertex " + std::to_string(v + 1), "coordinate is not finite");
    for (int d = 0; d < 3; ++d) {
      if (std::fabs(x[d]) > kMaxCoordinate)
        throw InputError(s.source, "vertex " + std::to_string(v + 1),
                         "coordinate " + number(x[d]) + " exceeds 1e30 in magnitude (rescale the mesh)");
      lo[d] = std::min(lo[d], x[d]);
      hi[d] = std::max(hi[d], x[d]);
    }
  }
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  if (extent < kMinExtent)
    throw InputError(s.source, "", "the mesh spans " + number(extent) + ", below 1e-30 (rescale the mesh)");
}

std::vector<char> check_indices(const TetSoup& s) {
  const std::size_t nv = s.points.size();
  if (is_mixed_or_surface(s))
    throw InputError(s.source, "",
                     "a " + std::string(s.other_cells.empty() ? "surface" : "mixed") + " mesh (" +
                         describe_cell_counts(mixed_cell_counts(s)) +
                         "): classify() takes tetrahedra only; the pipeline builds such a mesh's primal with "
                         "build_primal (classify/classify_primal.h)");
  if (!s.quads.empty())
    throw InputError(s.source, "", std::to_string(s.quads.size()) +
                                       " quadrangles on a tetrahedral mesh: no tetrahedron has a quadrangular face");
  if (s.tets.empty()) throw InputError(s.source, "", "mesh has no tetrahedra");
  if (s.tet_region.size() != s.tets.size())
    throw InputError(s.source, "", "region tags given for " + std::to_string(s.tet_region.size()) +
                                       " tets but the mesh has " + std::to_string(s.tets.size()));
  std::vector<char> used(nv, 0);
  for (std::size_t t = 0; t < s.tets.size(); ++t) {
    const auto& tv = s.tets[t];
    for (int i = 0; i < 4; ++i) {
      if (tv[i] >= nv)
        throw InputError(s.source, "tet " + std::to_string(t + 1),
                         "vertex index " + std::to_string(tv[i] + 1) + " out of range (1.." +
                             std::to_string(nv) + ")");
      for (int j = 0; j < i; ++j)
        if (tv[i] == tv[j])
          throw InputError(s.source, "tet " + std::to_string(t + 1),
                           "tet has zero volume (vertex " + std::to_string(tv[i] + 1) + " repeated)");
      used[tv[i]] = 1;
    }
  }
  check_coordinates(s, used);
  return used;
}

// Spatial order: used vertices along the Morton curve, tets by smallest vertex.
Compacted spatial_order(const TetSoup& s, std::vector<char> used) {
  const std::size_t nv = s.points.size();
  Compacted c;
  std::vector<std::uint32_t> used_list;
  std::vector<Point3> used_points;
  for (std::size_t v = 0; v < nv; ++v)
    if (used[v]) { used_list.push_back(std::uint32_t(v)); used_points.push_back(s.points[v]); }
  used = std::vector<char>();
  const std::vector<std::uint32_t> vorder = morton_order(used_points);
  used_points = std::vector<Point3>();
  c.remap.assign(nv, std::uint32_t(-1));
  c.input_vertex.resize(vorder.size());
  c.points.resize(vorder.size());
  for (std::size_t k = 0; k < vorder.size(); ++k) {
    const std::uint32_t v = used_list[vorder[k]];
    c.input_vertex[k] = v;
    c.remap[v] = std::uint32_t(k);
    c.points[k] = s.points[v];
  }
  // Tets by their smallest new vertex id: a stable counting sort straight from
  // the soup (no intermediate renumbered copy).
  const std::size_t nt = s.tets.size();
  auto renumbered = [&](std::size_t t) {
    const auto& tv = s.tets[t];
    return std::array<VertexId, 4>{VertexId(c.remap[tv[0]]), VertexId(c.remap[tv[1]]), VertexId(c.remap[tv[2]]),
                                   VertexId(c.remap[tv[3]])};
  };
  auto lowest = [](const std::array<VertexId, 4>& r) {
    return std::min(std::min(r[0].idx, r[1].idx), std::min(r[2].idx, r[3].idx));
  };
  std::vector<std::uint32_t> off(c.points.size() + 1, 0);
  for (std::size_t t = 0; t < nt; ++t) ++off[lowest(renumbered(t)) + 1];
  std::partial_sum(off.begin(), off.end(), off.begin());
  c.tets.resize(nt);
  c.regions.resize(nt);
  c.input_tet.resize(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const std::array<VertexId, 4> r = renumbered(t);
    const std::uint32_t k = off[lowest(r)]++;
    c.tets[k] = r;
    c.regions[k] = s.tet_region[t];
    c.input_tet[k] = std::uint32_t(t);
  }
  return c;
}

// "tets 3, 8, 12": up to ten 0-based input indices, 1-based, then how many more.
std::string tet_list(const std::vector<std::size_t>& tets) {
  std::string out = tets.size() == 1 ? "tet " : "tets ";
  for (std::size_t i = 0; i < tets.size() && i < 10; ++i) out += (i ? ", " : "") + std::to_string(tets[i] + 1);
  if (tets.size() > 10) out += " and " + std::to_string(tets.size() - 10) + " more";
  return out;
}

// The input indices (ascending) of the tets whose exact orientation is `sign`.
std::vector<std::size_t> tets_oriented(const Compacted& c, Sign sign) {
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < c.tets.size(); ++k) {
    const auto& tv = c.tets[k];
    if (orient3d(c.points[tv[0].idx], c.points[tv[1].idx], c.points[tv[2].idx], c.points[tv[3].idx]) == sign)
      out.push_back(c.input_tet[k]);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Mixed orientations: the tets of the smaller side are the inverted ones
// (ties: the negative ones, Gmsh's convention being positive).
[[noreturn]] void mixed_orientation_error(const TetSoup& s, const Compacted& c, std::size_t negative) {
  const std::size_t n = c.tets.size();
  const bool name_negative = negative <= n - negative;
  const std::vector<std::size_t> bad = tets_oriented(c, name_negative ? Sign::Negative : Sign::Positive);
  const std::string place = "tet " + std::to_string(bad.front() + 1);
  if (name_negative && bad.size() == 1)
    throw InputError(s.source, place, place + " is inverted (negative orientation)");
  const std::string what = name_negative ? " inverted (negative orientation, against the other " +
                                               std::to_string(n - bad.size()) + ")"
                                         : " inverted (positive orientation, against the other " +
                                               std::to_string(n - bad.size()) + ", negative ones)";
  throw InputError(s.source, place, std::to_string(bad.size()) + " of " + std::to_string(n) +
                                        (bad.size() == 1 ? " tets is" : " tets are") + what + ": " + tet_list(bad) +
                                        "; a mesh must orient all its tets the same way");
}

// EXACT: the orientation of every tet by orient3d (lib/predicates), in the
// new (cache-friendly) order. A degenerate tet is an error naming the first
// in input order. When every tet is negatively oriented, the mesh follows the
// other convention (Netgen's Gmsh export writes every tet so): each tet's last
// two vertices are swapped, which makes it positive, and the count is
// returned; mixed orientations are an error naming the inverted tets.
std::size_t orient_tets(const TetSoup& s, Compacted& c) {
  std::size_t negative = 0, zero = 0;
  for (const auto& tv : c.tets) {
    const Sign o = orient3d(c.points[tv[0].idx], c.points[tv[1].idx], c.points[tv[2].idx], c.points[tv[3].idx]);
    negative += o == Sign::Negative;
    zero += o == Sign::Zero;
  }
  if (zero > 0) {
    const std::size_t t = tets_oriented(c, Sign::Zero).front();
    throw InputError(s.source, "tet " + std::to_string(t + 1),
                     "tet " + std::to_string(t + 1) + " has zero volume (degenerate)");
  }
  if (negative == 0) return 0;
  if (negative < c.tets.size()) mixed_orientation_error(s, c, negative);
  for (auto& tv : c.tets) std::swap(tv[2], tv[3]);
  return negative;
}

Compacted validate_and_compact(const TetSoup& s, ClassifyStats& st) {
  using Clock = std::chrono::steady_clock;
  auto since = [](Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  auto t0 = Clock::now();
  std::vector<char> used = check_indices(s);
  st.seconds_validate = since(t0);
  t0 = Clock::now();
  Compacted c = spatial_order(s, std::move(used));
  st.seconds_order = since(t0);
  t0 = Clock::now();
  c.flipped = orient_tets(s, c);
  st.seconds_validate += since(t0);
  return c;
}

TriId find_triangle(const ClassifiedTetMesh& m, VertexId a, VertexId b, VertexId c) {
  for (TetId t : m.vertex_tets(a)) {
    int ib = m.local_index(t, b), ic = m.local_index(t, c);
    if (ib < 0 || ic < 0) continue;
    int ia = m.local_index(t, a);
    return m.tet_triangle(t, 6 - ia - ib - ic);
  }
  return TriId::invalid();
}

// The three edges of triangle f.
std::array<EdgeId, 3> triangle_edges(const ClassifiedTetMesh& m, TriId f) {
  TetId t = m.triangle_tet(f, 0);
  int i = 0;
  while (m.tet_triangle(t, i) != f) ++i;
  std::array<EdgeId, 3> out;
  int n = 0;
  for (int k = 0; k < 6; ++k)
    if (kTetEdge[k][0] != i && kTetEdge[k][1] != i) out[n++] = m.tet_edge(t, k);
  return out;
}

inline double degrees(double radians) { return radians * 180.0 / M_PI; }

// Bend angle (degrees) between two triangles sharing edge (a,b) with third
// vertices c1, c2: 0 when they continue each other in a plane. Inexact (double).
double bend_angle(const Point3& a, const Point3& b, const Point3& c1, const Point3& c2) {
  Vec3 e = b - a;
  Vec3 n1 = cross(e, c1 - a), n2 = cross(c2 - a, e);
  double d = norm(n1) * norm(n2);
  if (d == 0) return 180.0;  // a degenerate triangle: a full bend (split there)
  double cs = std::clamp(dot(n1, n2) / d, -1.0, 1.0);
  return degrees(std::acos(cs));
}

VertexId third_vertex(const ClassifiedTetMesh& m, TriId f, EdgeId e) {
  for (VertexId v : m.triangle(f))
    if (v != m.edge(e)[0] && v != m.edge(e)[1]) return v;
  return VertexId::invalid();
}

// Assign tags to components, in component order: the first component
// carrying a given tag keeps it; every other component gets a fresh tag.
// Fresh tags count up from one above the largest given tag (from 1 when none
// is given), so they never interleave with the file's; past INT32_MAX they are
// the smallest positive integers no component was given (below the largest
// given tag, so none of those handed out above it).
std::vector<std::int32_t> assign_tags(const std::vector<std::int32_t>& given_tag_of_component) {
  std::set<std::int32_t> given(given_tag_of_component.begin(), given_tag_of_component.end());
  given.erase(kNoTag);
  std::set<std::int32_t> kept;
  std::vector<std::int32_t> out(given_tag_of_component.size());
  std::int64_t above = given.empty() ? 1 : std::max<std::int64_t>(1, std::int64_t(*given.rbegin()) + 1);
  std::int32_t low = 1;
  for (std::size_t c = 0; c < out.size(); ++c) {
    std::int32_t g = given_tag_of_component[c];
    if (g != kNoTag && kept.insert(g).second) {
      out[c] = g;
      continue;
    }
    if (above <= std::numeric_limits<std::int32_t>::max()) {
      out[c] = std::int32_t(above++);
      continue;
    }
    while (given.count(low)) ++low;  // below the given ones: those above are all taken
    out[c] = low++;
  }
  return out;
}

// The tags in a warning: all of a few, else the first and last of a run.
std::string tag_list(const std::vector<std::int32_t>& tags) {
  std::string s;
  const bool run = tags.size() > 4 && tags.back() - tags.front() == std::int32_t(tags.size() - 1);
  if (run) return std::to_string(tags.front()) + ".." + std::to_string(tags.back());
  for (std::size_t i = 0; i < tags.size() && i < 4; ++i) s += (i ? ", " : "") + std::to_string(tags[i]);
  return tags.size() > 4 ? s + ", ..." : s;
}

// The model-face grouping key of a model-face triangle.
struct FaceKey {
  std::int32_t given, r0, r1;  // r1 = kNoTag on the external boundary
  auto operator<=>(const FaceKey&) const = default;
};

// A candidate model edge: an edge with a model-face triangle or a given tag.
struct Cand {
  std::uint32_t e, t0, t1;  // the edge; its model-face triangles are et[t0 .. t1)
  std::int32_t given;       // given model-edge tag or kNoTag
};

// The inference of the model's faces, edges and vertices (design §3) on a mesh
// with its topology built, one phase per member function, in this order.
// Everything works on sparse lists: the model-face triangles (a few per cent
// of all triangles, in the order of their sorted vertex ids: rank_by_vertices)
// and the candidate model edges (in increasing id order, which is the order of
// their vertex ids), so the components and tags depend on the boundary alone.
class ModelInference {
 public:
  ModelInference(const TetSoup& soup, const ClassifyParams& params, const std::vector<std::uint32_t>& remap,
                 ClassifiedTetMesh& m)
      : soup_(soup), params_(params), remap_(remap), m_(m), tri_face_(TetMeshBuilder::triangle_face(m)) {}

  void run() {
    read_given_triangles();
    find_model_face_triangles();
    find_candidate_edges();
    group_model_faces();
    find_model_edges();
    find_model_vertices();
    classify_edges();
    classify_vertices();
    build_model_topology();
    name_model_entities();
    report_completion();
    report_markers();
  }

 private:
  VertexId remap(std::uint32_t v, const char* what, std::size_t i) const {
    if (v >= remap_.size() || remap_[v] == std::uint32_t(-1))
      throw InputError(soup_.source, std::string(what) + " " + std::to_string(i + 1),
                       "vertex index " + std::to_string(v + 1) + " is out of range or used by no tet");
    return VertexId(remap_[v]);
  }
  std::int32_t given_of(std::size_t f) const { return tri_given_.empty() ? kNoTag : tri_given_[f]; }
  // Distinct model-face tags around candidate edge ci (sorted).
  std::vector<std::int32_t> edge_faces(std::size_t ci) const {
    std::vector<std::int32_t> tags;
    for (std::uint32_t k = cand_[ci].t0; k < cand_[ci].t1; ++k) tags.push_back(tri_face_[mf_[et_[k].r]]);
    std::sort(tags.begin(), tags.end());
    tags.erase(std::unique(tags.begin(), tags.end()), tags.end());
    return tags;
  }
  // The model edges at vertex v (candidate indices, increasing).
  std::span<const std::uint32_t> v_me(std::size_t v) const {
    return {vme_.data() + vme_off_[v], vme_.data() + vme_off_[v + 1]};
  }
  auto edge_key(std::uint32_t ci) const { return std::make_pair(cand_[ci].given, edge_faces(ci)); }

  void read_given_triangles();
  void find_model_face_triangles();
  void rank_by_vertices();
  void find_candidate_edges();
  std::array<VertexId, 3> oriented_triangle(std::uint32_t r) const;
  void orient_sheets();
  BendEdge bend_edge(std::size_t ci, std::uint32_t f1, std::uint32_t f2) const;
  void judge_bends();
  void group_model_faces();
  void find_model_edges();
  VertexId across(std::uint32_t ci, std::size_t v) const;
  double turn_at(std::size_t v) const;
  bool is_model_vertex(std::size_t v) const;
  void find_model_vertices();
  void classify_edges();
  void classify_vertices();
  void build_model_topology();
  void name_model_entities();
  void report_completion();
  void report_markers();
  // Records a fresh tag that classify() gave in a full classification (see
  // Added) at the place `where`, for report_completion().
  void note_added(int dim, std::int32_t given, std::int32_t tag, const std::string& where);
  std::string edge_place(std::size_t ci) const {
    const auto v = m_.edge(EdgeId(cand_[ci].e));
    return "edge " + vlist({m_.input_vertex(v[0]), m_.input_vertex(v[1])});
  }
  std::string vertex_place(std::size_t v) const { return "vertex " + std::to_string(m_.input_vertex(VertexId(v)) + 1); }
  // Per curve tag of a full classification: its first edge and the file's
  // surface tags around it (check_curve_faces).
  struct CurveSurfaces {
    struct First {
      std::size_t ci;
      std::uint32_t offset, size;  // in pool
    };
    std::unordered_map<std::int32_t, First> first;
    std::vector<std::int32_t> pool, scratch;
  };
  void check_curve_faces(std::size_t ci, CurveSurfaces& seen);

  const TetSoup& soup_;
  const ClassifyParams& params_;
  // The feature angle splits given face markers too, unless the file gave a
  // full classification (whose surfaces are the model's faces as they are).
  const bool split_markers_ = !soup_.full_classification;
  // Model entities a full classification did not have, by dimension:
  // inferred ones (no file tag) and pieces of one file tag beyond the first.
  struct Added {
    std::vector<std::int32_t> tags;
    std::string first_where;
    std::int32_t first_given = kNoTag;
  };
  std::array<Added, 3> inferred_, pieces_;
  const std::vector<std::uint32_t>& remap_;  // soup vertex index -> vertex id (or -1)
  ClassifiedTetMesh& m_;
  std::vector<std::int32_t>& tri_face_;      // the mesh's model-face tag per triangle
  std::vector<std::int32_t> tri_given_;      // given triangle tags (dense; empty when none given)
  std::vector<std::uint32_t> mf_;            // the model-face triangle of each rank
  std::vector<FaceKey> key_;                 // by rank
  struct EdgeTri { std::uint32_t e, r; };
  std::vector<EdgeTri> et_;                  // (edge, rank) incidences sorted by edge
  std::vector<Cand> cand_;
  std::vector<char> is_me_;                  // per candidate: a model edge
  static constexpr std::uint8_t kNotTested = 0xff;
  std::vector<std::uint8_t> verdict_;        // per candidate: its FeatureVerdict, or kNotTested
  std::vector<char> sheet_flip_;             // per rank in a one-region sheet: reversed (orient_sheets)
  std::vector<std::uint32_t> vme_off_, vme_; // vertex -> model edges (CSR of candidates)
  std::vector<std::int32_t> corner_given_;   // per vertex: given model-vertex tag or kNoTag
  std::vector<char> is_mv_;                  // per vertex: a model vertex
  std::vector<std::int32_t> v_face_;         // per vertex: a model face it is on, or kNoTag
  std::vector<char> v_multi_face_;           // per vertex: on two model faces or more
  std::vector<std::int32_t> edge_tag_, ecomp_;  // model-edge tags, by component of each candidate
};

// Given triangle tags, looked up by triangle (none given: no array).
void ModelInference::read_given_triangles() {
  if (!soup_.triangles.empty()) tri_given_.assign(m_.num_triangles(), kNoTag);
  for (std::size_t i = 0; i < soup_.triangles.size(); ++i) {
    const auto& t = soup_.triangles[i];
    VertexId a = remap(t.v[0], "triangle", i), b = remap(t.v[1], "triangle", i), c = remap(t.v[2], "triangle", i);
    if (a == b || b == c || a == c)
      throw InputError(soup_.source, "triangle " + std::to_string(i + 1),
                       "triangle " + vlist({t.v[0], t.v[1], t.v[2]}) + " repeats a vertex");
    TriId f = find_triangle(m_, a, b, c);
    if (!f.valid())
      throw InputError(soup_.source, "triangle " + std::to_string(i + 1),
                       "triangle " + vlist({t.v[0], t.v[1], t.v[2]}) + " is not a face of any tet");
    if (tri_given_[f.idx] != kNoTag && tri_given_[f.idx] != t.tag)
      throw InputError(soup_.source, "triangle " + std::to_string(i + 1),
                       "triangle classified on two model faces (" + std::to_string(tri_given_[f.idx]) + " and " +
                           std::to_string(t.tag) + ")");
    tri_given_[f.idx] = t.tag;
  }
}

// Model-face triangles: on the external boundary, between two regions, or
// given a tag; each with its grouping key.
void ModelInference::find_model_face_triangles() {
  for (std::size_t f = 0; f < m_.num_triangles(); ++f) {
    TetId t0 = m_.triangle_tet(TriId(f), 0), t1 = m_.triangle_tet(TriId(f), 1);
    std::int32_t r0 = m_.region(t0), r1 = t1.valid() ? m_.region(t1) : kNoTag;
    bool topo = !t1.valid() || r0 != r1;
    const std::int32_t given = given_of(f);
    if (!topo && given == kNoTag) continue;
    if (topo && soup_.full_classification && given == kNoTag) {
      const auto& v = m_.triangle(TriId(f));
      throw InputError(soup_.source,
                       "triangle " + vlist({m_.input_vertex(v[0]), m_.input_vertex(v[1]), m_.input_vertex(v[2])}),
                       std::string("contradiction: the triangle lies ") +
                           (t1.valid() ? "between regions " + std::to_string(r0) + " and " + std::to_string(r1)
                                       : "on the external boundary") +
                           " but the file classifies it on no model face");
    }
    if (r1 != kNoTag && r1 < r0) std::swap(r0, r1);
    mf_.push_back(std::uint32_t(f));
    key_.push_back({given, r0, r1});
  }
  rank_by_vertices();
}

// Ranks in the order of the triangles' sorted vertex ids, not of triangle ids:
// triangles are numbered from the tets (first occurrence), vertices from the
// points alone (spatial_order.h), so the model faces' components, which
// piece of a marker keeps its tag and the fresh tags come out the same for
// the same boundary whatever tets fill the regions (Delaunay flips renumber
// them). Model edges and vertices are numbered by vertex ids already.
void ModelInference::rank_by_vertices() {
  std::vector<std::pair<std::array<std::uint32_t, 3>, std::uint32_t>> order(mf_.size());
  for (std::uint32_t r = 0; r < mf_.size(); ++r) {
    const auto v = m_.triangle(TriId(mf_[r]));
    std::array<std::uint32_t, 3> s{v[0].idx, v[1].idx, v[2].idx};
    std::sort(s.begin(), s.end());
    order[r] = {s, r};
  }
  std::sort(order.begin(), order.end());
  std::vector<std::uint32_t> mf(mf_.size());
  std::vector<FaceKey> key(key_.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    mf[k] = mf_[order[k].second];
    key[k] = key_[order[k].second];
  }
  mf_ = std::move(mf);
  key_ = std::move(key);
}

// Candidate edges: (edge, rank) incidences sorted by edge (ranks increasing
// within an edge), merged with the given edges.
void ModelInference::find_candidate_edges() {
  const std::size_t nmf = mf_.size();
  et_.reserve(3 * nmf);
  for (std::size_t r = 0; r < nmf; ++r)
    for (EdgeId e : triangle_edges(m_, TriId(mf_[r]))) et_.push_back({e.idx, std::uint32_t(r)});
  // Stable by edge: records were made in rank order, so ranks stay increasing.
  radix_sort_by_key(et_, [](const EdgeTri& x) { return x.e; }, std::bit_width(m_.num_edges()));
  std::vector<std::pair<std::uint32_t, std::int32_t>> given_edges;  // (edge, tag), the last given wins
  for (std::size_t i = 0; i < soup_.edges.size(); ++i) {
    VertexId a = remap(soup_.edges[i].v[0], "edge", i), b = remap(soup_.edges[i].v[1], "edge", i);
    if (a == b) throw InputError(soup_.source, "edge " + std::to_string(i + 1), "edge repeats a vertex");
    EdgeId e = m_.find_edge(a, b);
    if (!e.valid())
      throw InputError(soup_.source, "edge " + std::to_string(i + 1),
                       "edge " + vlist({soup_.edges[i].v[0], soup_.edges[i].v[1]}) + " is not an edge of any tet");
    given_edges.emplace_back(e.idx, soup_.edges[i].tag);
  }
  std::stable_sort(given_edges.begin(), given_edges.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  std::size_t i = 0, g = 0;
  while (i < et_.size() || g < given_edges.size()) {
    const std::uint32_t e = std::min(i < et_.size() ? et_[i].e : UINT32_MAX,
                                     g < given_edges.size() ? given_edges[g].first : UINT32_MAX);
    Cand c{e, std::uint32_t(i), std::uint32_t(i), kNoTag};
    while (i < et_.size() && et_[i].e == e) ++i;
    c.t1 = std::uint32_t(i);
    while (g < given_edges.size() && given_edges[g].first == e) c.given = given_edges[g++].second;
    cand_.push_back(c);
  }
}

// The triangle of rank r, oriented so that its right-hand normal points out
// of the first region of its key, or (a sheet inside one region: a fracture)
// as orient_sheets() turned it, so the triangles of one sheet are oriented
// alike whatever the tets around them.
std::array<VertexId, 3> ModelInference::oriented_triangle(std::uint32_t r) const {
  std::array<VertexId, 3> v = m_.triangle(TriId(mf_[r]));
  const bool out_of_r0 = m_.region(m_.triangle_tet(TriId(mf_[r]), 0)) == key_[r].r0;
  if (key_[r].r0 == key_[r].r1 ? sheet_flip_[r] != 0 : !out_of_r0) std::swap(v[1], v[2]);
  return v;
}

// True when the triangle's boundary runs a -> b.
bool runs_from_to(const std::array<VertexId, 3>& t, VertexId a, VertexId b) {
  for (int k = 0; k < 3; ++k)
    if (t[k] == a && t[(k + 1) % 3] == b) return true;
  return false;
}

// A sheet inside one region has no "out of the first region": each triangle
// is oriented out of its first tet, which is a matter of tet numbering (it
// changes when flips renumber the tets). Its triangles are oriented alike by a
// walk across the edges between exactly two of them from the first triangle
// of each piece; a consistent orientation is unique up to reversing a whole
// piece, which FE1's tests do not see (left and right swap and both negate).
// Combinatorial, no geometry. On a non-orientable piece (a Möbius band) the
// edges where the walk disagrees get no normals (bend_edge: no chain there).
void ModelInference::orient_sheets() {
  const std::size_t nmf = mf_.size();
  sheet_flip_.assign(nmf, 0);
  std::vector<std::uint32_t> off(nmf + 1, 0), adj;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (std::uint32_t ci = 0; ci < cand_.size(); ++ci) {
    const Cand& c = cand_[ci];
    if (c.t1 - c.t0 != 2) continue;
    const std::uint32_t f1 = et_[c.t0].r, f2 = et_[c.t0 + 1].r;
    if (!(key_[f1] == key_[f2]) || key_[f1].r0 != key_[f1].r1) continue;
    pairs.emplace_back(f1, ci);  // (rank, candidate): the walk's adjacency
    pairs.emplace_back(f2, ci);
  }
  std::sort(pairs.begin(), pairs.end());
  for (const auto& [f, ci] : pairs) ++off[f + 1];
  std::partial_sum(off.begin(), off.end(), off.begin());
  std::vector<char> seen(nmf, 0);
  std::vector<std::uint32_t> stack;
  for (std::uint32_t r0 = 0; r0 < nmf; ++r0) {
    if (seen[r0] || off[r0] == off[r0 + 1]) continue;
    seen[r0] = 1;
    stack.assign(1, r0);
    while (!stack.empty()) {
      const std::uint32_t f = stack.back();
      stack.pop_back();
      for (std::uint32_t k = off[f]; k < off[f + 1]; ++k) {
        const Cand& c = cand_[pairs[k].second];
        const std::uint32_t g = et_[c.t0].r == f ? et_[c.t0 + 1].r : et_[c.t0].r;
        if (seen[g]) continue;
        const auto ev = m_.edge(EdgeId(c.e));
        // g runs the edge the other way round from f once oriented.
        sheet_flip_[g] = runs_from_to(oriented_triangle(f), ev[0], ev[1]) ==
                         runs_from_to(m_.triangle(TriId(mf_[g])), ev[0], ev[1]);
        seen[g] = 1;
        stack.push_back(g);
      }
    }
  }
}

// The bend at candidate ci (two model-face triangles of ranks f1, f2), with
// the oriented normals on its left and right (classify/features.h).
BendEdge ModelInference::bend_edge(std::size_t ci, std::uint32_t f1, std::uint32_t f2) const {
  const auto ev = m_.edge(EdgeId(cand_[ci].e));
  BendEdge b;
  b.a = ev[0].idx;
  b.b = ev[1].idx;
  b.dir = m_.point(ev[1]) - m_.point(ev[0]);
  b.bend = bend_angle(m_.point(ev[0]), m_.point(ev[1]), m_.point(third_vertex(m_, TriId(mf_[f1]), EdgeId(cand_[ci].e))),
                      m_.point(third_vertex(m_, TriId(mf_[f2]), EdgeId(cand_[ci].e))));
  auto runs_ab = [&](const std::array<VertexId, 3>& t) { return runs_from_to(t, ev[0], ev[1]); };
  auto unit_normal = [&](const std::array<VertexId, 3>& t) {
    const Vec3 n = cross(m_.point(t[1]) - m_.point(t[0]), m_.point(t[2]) - m_.point(t[0]));
    const double len = norm(n);
    return len > 0 ? n / len : Vec3{};
  };
  const auto t1 = oriented_triangle(f1), t2 = oriented_triangle(f2);
  if (runs_ab(t1) != runs_ab(t2)) {  // one sheet, oriented alike: the edge runs both ways
    b.left = unit_normal(runs_ab(t1) ? t1 : t2);
    b.right = unit_normal(runs_ab(t1) ? t2 : t1);
  }
  return b;
}

// The feature verdict of every candidate inside one sheet (two model-face
// triangles of one key) where the feature angle applies; kNotTested elsewhere.
void ModelInference::judge_bends() {
  std::vector<BendEdge> bends;
  std::vector<std::uint32_t> which;
  verdict_.assign(cand_.size(), kNotTested);
  orient_sheets();
  for (std::size_t ci = 0; ci < cand_.size(); ++ci) {
    const Cand& c = cand_[ci];
    if (c.t1 - c.t0 != 2) continue;
    const std::uint32_t f1 = et_[c.t0].r, f2 = et_[c.t0 + 1].r;
    if (!(key_[f1] == key_[f2]) || !(key_[f1].given == kNoTag || split_markers_)) continue;
    bends.push_back(bend_edge(ci, f1, f2));
    which.push_back(std::uint32_t(ci));
  }
  const FeatureRule rule{params_.feature_angle_deg, std::max(params_.feature_angle_deg, params_.strong_angle_deg),
                         params_.min_feature_chain_edges};
  const std::vector<FeatureVerdict> v = select_feature_edges(bends, rule);
  for (std::size_t k = 0; k < which.size(); ++k) verdict_[which[k]] = std::uint8_t(v[k]);
}

// Model faces: model-face triangles united across edges with exactly two of
// them, of equal keys, and (where the feature angle applies) no feature edge
// between them (judge_bends).
void ModelInference::group_model_faces() {
  const std::size_t nmf = mf_.size();
  judge_bends();
  UnionFind uf(nmf);
  for (std::size_t ci = 0; ci < cand_.size(); ++ci) {
    const Cand& c = cand_[ci];
    if (c.t1 - c.t0 != 2) continue;
    const std::uint32_t f1 = et_[c.t0].r, f2 = et_[c.t0 + 1].r;
    if (!(key_[f1] == key_[f2])) continue;
    if (verdict_[ci] == std::uint8_t(FeatureVerdict::Strong) || verdict_[ci] == std::uint8_t(FeatureVerdict::Chain))
      continue;
    uf.unite(f1, f2);
  }
  std::vector<std::int32_t> comp_of(nmf, -1), comp_given;
  std::vector<std::uint32_t> comp_first;  // per component: its first rank
  std::vector<std::uint32_t> root_comp(nmf, std::uint32_t(-1));
  for (std::size_t r = 0; r < nmf; ++r) {
    const std::uint32_t root = uf.find(r);
    if (root_comp[root] == std::uint32_t(-1)) {
      root_comp[root] = std::uint32_t(comp_given.size());
      comp_given.push_back(key_[r].given);
      comp_first.push_back(std::uint32_t(r));
    }
    comp_of[r] = std::int32_t(root_comp[root]);
  }
  const std::vector<std::int32_t> face_tag = assign_tags(comp_given);
  for (std::size_t r = 0; r < nmf; ++r) tri_face_[mf_[r]] = face_tag[comp_of[r]];
  if (!soup_.full_classification) return;
  for (std::size_t c = 0; c < comp_given.size(); ++c) {
    if (face_tag[c] == comp_given[c]) continue;
    const auto& v = m_.triangle(TriId(mf_[comp_first[c]]));
    note_added(2, comp_given[c], face_tag[c],
               "triangle " + vlist({m_.input_vertex(v[0]), m_.input_vertex(v[1]), m_.input_vertex(v[2])}));
  }
}

// In a full classification, a curve lies on the same surfaces all along
// (in Gmsh, a curve entity bounds or is embedded in fixed surfaces): the
// file's surface tags around a given edge must be those around the first edge
// of its curve, else the file contradicts itself (named at both edges). The
// first edge's sorted tags are kept in one pool (no allocation per edge).
void ModelInference::check_curve_faces(std::size_t ci, CurveSurfaces& seen) {
  std::vector<std::int32_t>& here = seen.scratch;
  here.clear();
  for (std::uint32_t k = cand_[ci].t0; k < cand_[ci].t1; ++k) here.push_back(key_[et_[k].r].given);
  std::sort(here.begin(), here.end());
  here.erase(std::unique(here.begin(), here.end()), here.end());
  const auto [it, first] = seen.first.try_emplace(
      cand_[ci].given, CurveSurfaces::First{ci, std::uint32_t(seen.pool.size()), std::uint32_t(here.size())});
  if (first) {
    seen.pool.insert(seen.pool.end(), here.begin(), here.end());
    return;
  }
  const CurveSurfaces::First& f = it->second;
  const std::span<const std::int32_t> there(seen.pool.data() + f.offset, f.size);
  if (std::equal(there.begin(), there.end(), here.begin(), here.end())) return;
  auto set = [](std::span<const std::int32_t> v) {
    std::string s = "{";
    for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + std::to_string(v[i]);
    return s + "}";
  };
  throw InputError(soup_.source, edge_place(ci),
                   "contradiction: the file classifies this edge on curve " + std::to_string(cand_[ci].given) +
                       ", whose " + edge_place(f.ci) + " lies on surfaces " + set(there) +
                       ", but the triangles at this edge lie on surfaces " + set(here));
}

// Model edges: candidates where the model-face triangles do not form one
// smooth sheet (not exactly two, or of two model faces), or given a tag; and
// each vertex's model edges.
void ModelInference::find_model_edges() {
  const std::size_t nc = cand_.size(), nv = m_.num_vertices();
  is_me_.assign(nc, 0);
  CurveSurfaces curve_faces;
  for (std::size_t ci = 0; ci < nc; ++ci) {
    const std::uint32_t n = cand_[ci].t1 - cand_[ci].t0;
    const std::vector<std::int32_t> tags = n > 0 ? edge_faces(ci) : std::vector<std::int32_t>{};
    bool topo = n > 0 && (n != 2 || tags.size() >= 2);
    if (soup_.full_classification && cand_[ci].given != kNoTag) check_curve_faces(ci, curve_faces);
    is_me_[ci] = topo || cand_[ci].given != kNoTag;
  }
  vme_off_.assign(nv + 1, 0);
  for (std::size_t ci = 0; ci < nc; ++ci)
    if (is_me_[ci])
      for (VertexId v : m_.edge(EdgeId(cand_[ci].e))) ++vme_off_[v.idx + 1];
  std::partial_sum(vme_off_.begin(), vme_off_.end(), vme_off_.begin());
  vme_.resize(vme_off_[nv]);
  std::vector<std::uint32_t> fill(vme_off_.begin(), vme_off_.end() - 1);
  for (std::size_t ci = 0; ci < nc; ++ci)
    if (is_me_[ci])
      for (VertexId v : m_.edge(EdgeId(cand_[ci].e))) vme_[fill[v.idx]++] = std::uint32_t(ci);
}

// The other end of model-edge candidate ci at vertex v.
VertexId ModelInference::across(std::uint32_t ci, std::size_t v) const {
  const auto e = m_.edge(EdgeId(cand_[ci].e));
  return e[0] == VertexId(v) ? e[1] : e[0];
}

// The turn (degrees) of an inferred model edge at v, where exactly two of its
// segments meet with one key; 0 where no such curve passes through v.
double ModelInference::turn_at(std::size_t v) const {
  const auto es = v_me(v);
  if (corner_given_[v] != kNoTag || es.size() != 2 || cand_[es[0]].given != kNoTag ||
      cand_[es[1]].given != kNoTag || edge_key(es[0]) != edge_key(es[1]))
    return 0;
  const Point3& p = m_.point(VertexId(v));
  return angle_deg(p - m_.point(across(es[0], v)), m_.point(across(es[1], v)) - p);
}

// A vertex is a model vertex if given one, where model faces touch without a
// model edge, where model edges end, branch or change key, or where an
// inferred model edge kinks: turns above the feature angle between
// neighbours that turn by at most half of it (not the even turning of a
// coarse curve, nor the zigzag of a curve traced through a labelled image).
// Double geometry, like the bends.
bool ModelInference::is_model_vertex(std::size_t v) const {
  const auto es = v_me(v);
  if (corner_given_[v] != kNoTag) return true;
  if (es.empty()) return v_multi_face_[v] != 0;
  if (es.size() != 2 || edge_key(es[0]) != edge_key(es[1])) return true;
  if (cand_[es[0]].given != kNoTag) return false;
  const double turn = turn_at(v);
  if (turn <= params_.feature_angle_deg) return false;
  for (std::uint32_t ci : es)
    if (turn_at(across(ci, v).idx) > params_.feature_angle_deg / 2) return false;
  return true;
}

void ModelInference::find_model_vertices() {
  const std::size_t nv = m_.num_vertices();
  corner_given_.assign(nv, kNoTag);
  for (std::size_t i = 0; i < soup_.corners.size(); ++i)
    corner_given_[remap(soup_.corners[i].v, "corner", i).idx] = soup_.corners[i].tag;
  // Distinct model faces at each vertex (for vertices where faces touch without an edge).
  v_face_.assign(nv, kNoTag);
  v_multi_face_.assign(nv, 0);
  for (std::size_t r = 0; r < mf_.size(); ++r) {
    const std::int32_t t = tri_face_[mf_[r]];
    for (VertexId v : m_.triangle(TriId(mf_[r]))) {
      if (v_face_[v.idx] == kNoTag) v_face_[v.idx] = t;
      else if (v_face_[v.idx] != t) v_multi_face_[v.idx] = 1;
    }
  }
  is_mv_.assign(nv, 0);
  for (std::size_t v = 0; v < nv; ++v) is_mv_[v] = is_model_vertex(v);
}

// Model edges: components of model-edge primal edges with equal keys, joined
// at vertices that are not model vertices; then every edge's class.
void ModelInference::classify_edges() {
  const std::size_t nc = cand_.size(), nv = m_.num_vertices(), ne = m_.num_edges();
  UnionFind ue(nc);
  for (std::size_t v = 0; v < nv; ++v)
    if (!is_mv_[v] && v_me(v).size() == 2) ue.unite(v_me(v)[0], v_me(v)[1]);
  std::vector<std::int32_t> ecomp_given;
  std::vector<std::uint32_t> ecomp_first;  // per component: its first candidate
  ecomp_.assign(nc, -1);
  std::vector<std::uint32_t> eroot(nc, std::uint32_t(-1));
  for (std::size_t ci = 0; ci < nc; ++ci) {
    if (!is_me_[ci]) continue;
    std::uint32_t r = ue.find(ci);
    if (eroot[r] == std::uint32_t(-1)) {
      eroot[r] = std::uint32_t(ecomp_given.size());
      ecomp_given.push_back(cand_[ci].given);
      ecomp_first.push_back(std::uint32_t(ci));
    }
    ecomp_[ci] = std::int32_t(eroot[r]);
  }
  edge_tag_ = assign_tags(ecomp_given);
  if (soup_.full_classification)
    for (std::size_t c = 0; c < ecomp_given.size(); ++c)
      if (edge_tag_[c] != ecomp_given[c]) note_added(1, ecomp_given[c], edge_tag_[c], edge_place(ecomp_first[c]));
  auto& edge_class = TetMeshBuilder::edge_class(m_);
  // An edge with no model-face triangle lies in one region: any of its tets.
  for (std::size_t e = 0; e < ne; ++e) edge_class[e] = ModelRef{3, m_.region(m_.edge_tet(EdgeId(e)))};
  for (std::size_t ci = 0; ci < nc; ++ci) {
    if (is_me_[ci])
      edge_class[cand_[ci].e] = ModelRef{1, edge_tag_[ecomp_[ci]]};
    else if (cand_[ci].t1 > cand_[ci].t0)
      edge_class[cand_[ci].e] = ModelRef{2, tri_face_[mf_[et_[cand_[ci].t0].r]]};
  }
}

// Model vertices get tags in vertex order; every other vertex takes the class
// of its model edge, else its model face, else its region.
void ModelInference::classify_vertices() {
  const std::size_t nv = m_.num_vertices();
  std::vector<std::int32_t> vgiven;
  std::vector<std::uint32_t> mv_list;
  for (std::size_t v = 0; v < nv; ++v)
    if (is_mv_[v]) { mv_list.push_back(std::uint32_t(v)); vgiven.push_back(corner_given_[v]); }
  const std::vector<std::int32_t> vtag = assign_tags(vgiven);
  auto& vclass = TetMeshBuilder::vertex_class(m_);
  const auto& edge_class = TetMeshBuilder::edge_class(m_);
  for (std::size_t i = 0; i < mv_list.size(); ++i) vclass[mv_list[i]] = ModelRef{0, vtag[i]};
  if (soup_.full_classification)
    for (std::size_t i = 0; i < mv_list.size(); ++i)
      if (vtag[i] != vgiven[i]) note_added(0, vgiven[i], vtag[i], vertex_place(mv_list[i]));
  for (std::size_t v = 0; v < nv; ++v) {
    if (is_mv_[v]) continue;
    if (!v_me(v).empty()) vclass[v] = edge_class[cand_[v_me(v)[0]].e];
    else if (v_face_[v] != kNoTag) vclass[v] = ModelRef{2, v_face_[v]};
    else vclass[v] = ModelRef{3, m_.region(m_.vertex_tets(VertexId(v)).front())};
  }
}

// The model's entities by dimension, sorted by tag, each with what it bounds.
void ModelInference::build_model_topology() {
  ModelTopology& topo = TetMeshBuilder::model(m_);
  const auto& edge_class = TetMeshBuilder::edge_class(m_);
  const auto& vclass = TetMeshBuilder::vertex_class(m_);
  std::map<std::int32_t, ModelEntity> regions, faces, edges, verts;
  for (std::size_t t = 0; t < m_.num_tets(); ++t) {
    const std::int32_t tag = m_.region(TetId(t));
    if (t > 0 && tag == m_.region(TetId(t - 1))) continue;  // runs of one region: skip the map
    auto& r = regions[tag];
    r.dim = 3;
    r.tag = tag;
    r.source_tag = tag;
  }
  for (std::size_t r = 0; r < mf_.size(); ++r) {
    auto& e = faces[tri_face_[mf_[r]]];
    if (e.regions.empty()) {
      e.dim = 2;
      e.tag = tri_face_[mf_[r]];
      e.regions.push_back(key_[r].r0);
      if (key_[r].r1 != kNoTag) e.regions.push_back(key_[r].r1);
      e.bounds = e.regions;
      e.bounds.erase(std::unique(e.bounds.begin(), e.bounds.end()), e.bounds.end());
      if (key_[r].given != kNoTag) e.source_tag = key_[r].given;
    }
  }
  for (std::size_t ci = 0; ci < cand_.size(); ++ci) {
    if (!is_me_[ci]) continue;
    auto& me = edges[edge_class[cand_[ci].e].tag];
    me.dim = 1;
    me.tag = edge_class[cand_[ci].e].tag;
    if (cand_[ci].given != kNoTag) me.source_tag = cand_[ci].given;
    const std::vector<std::int32_t> tags = edge_faces(ci);
    me.bounds.insert(me.bounds.end(), tags.begin(), tags.end());
  }
  for (std::size_t v = 0; v < m_.num_vertices(); ++v) {
    if (!is_mv_[v]) continue;
    auto& mv = verts[vclass[v].tag];
    mv.dim = 0;
    mv.tag = vclass[v].tag;
    if (corner_given_[v] != kNoTag) mv.source_tag = corner_given_[v];
    for (std::uint32_t ci : v_me(v)) mv.bounds.push_back(edge_class[cand_[ci].e].tag);
  }
  auto finish = [](std::map<std::int32_t, ModelEntity>& src, std::vector<ModelEntity>& dst) {
    dst.clear();
    for (auto& [tag, ent] : src) {
      std::sort(ent.bounds.begin(), ent.bounds.end());
      ent.bounds.erase(std::unique(ent.bounds.begin(), ent.bounds.end()), ent.bounds.end());
      dst.push_back(std::move(ent));
    }
  };
  finish(verts, topo.entities[0]);
  finish(edges, topo.entities[1]);
  finish(faces, topo.entities[2]);
  finish(regions, topo.entities[3]);
}

// Each model entity with a file tag takes the tags of all the groups
// (TetSoup::groups, sorted by (dim, tag)) of its dimension listing that tag,
// and the name of the first named one.
void ModelInference::name_model_entities() {
  std::map<std::pair<int, std::int32_t>, const std::string*> name_of;
  std::map<std::pair<int, std::int32_t>, std::vector<std::int32_t>> groups_of;
  for (const NamedGroup& g : soup_.groups)
    if (g.dim >= 0 && g.dim <= 3)
      for (std::int32_t t : g.entities) {
        groups_of[{g.dim, t}].push_back(g.tag);
        if (!g.name.empty()) name_of.try_emplace({g.dim, t}, &g.name);
      }
  if (groups_of.empty()) return;
  for (auto& ents : TetMeshBuilder::model(m_).entities)
    for (ModelEntity& e : ents) {
      if (!e.source_tag) continue;
      if (auto it = name_of.find({e.dim, *e.source_tag}); it != name_of.end()) e.name = *it->second;
      if (auto it = groups_of.find({e.dim, *e.source_tag}); it != groups_of.end()) e.groups = it->second;
    }
}

void ModelInference::note_added(int dim, std::int32_t given, std::int32_t tag, const std::string& where) {
  Added& a = given == kNoTag ? inferred_[dim] : pieces_[dim];
  if (a.tags.empty()) {
    a.first_where = where;
    a.first_given = given;
  }
  a.tags.push_back(tag);
}

// One warning per kind of model entity a full classification lacked: the
// count, the fresh tags and the first place (in mesh order).
void ModelInference::report_completion() {
  static constexpr const char* kEntity[3][2] = {
      {"model vertex", "model vertices"}, {"model edge", "model edges"}, {"model face", "model faces"}};
  static constexpr const char* kFileEntity[3] = {"point", "curve", "surface"};
  static constexpr const char* kWhereInferred[3] = {
      "where model edges end, branch or change curve at no point of the file",
      "where model faces meet along edges that no curve of the file covers",
      ""};  // never: every model-face triangle of a full classification has a surface
  static constexpr const char* kWhyPieces[3] = {
      "one point tag given to several vertices", "split at a model vertex, or disconnected",
      "disconnected, or between different regions"};
  auto& out = TetMeshBuilder::classification_warnings(m_);
  for (int d = 0; d < 3; ++d) {
    auto sorted = [](std::vector<std::int32_t> t) { std::sort(t.begin(), t.end()); return t; };
    const Added& inf = inferred_[d];
    if (!inf.tags.empty())
      out.push_back(soup_.source + ": incomplete classification completed by inference: " +
                    std::to_string(inf.tags.size()) + " " + kEntity[d][inf.tags.size() > 1] + " added (tags " +
                    tag_list(sorted(inf.tags)) + ") " + kWhereInferred[d] + ", the first at " + inf.first_where);
    const Added& pc = pieces_[d];
    if (!pc.tags.empty())
      out.push_back(soup_.source + ": " + std::to_string(pc.tags.size()) + " " + kEntity[d][pc.tags.size() > 1] +
                    " added (tags " + tag_list(sorted(pc.tags)) + ") for pieces of the file's " + kFileEntity[d] +
                    "s that are not one " + kEntity[d][0] + " (" + kWhyPieces[d] + "), the first: " +
                    kFileEntity[d] + " " + std::to_string(pc.first_given) + " at " + pc.first_where);
  }
}

// Per face marker (kNoTag first: the untagged triangles): its triangles, the
// model faces, edges and vertices on them, and the verdicts on its sharp
// edges (ClassifiedTetMesh::marker_features()).
void ModelInference::report_markers() {
  if (soup_.full_classification) return;
  struct Acc {
    MarkerFeatures out;
    std::set<std::int32_t> faces, edges, corners;
  };
  std::map<std::int32_t, Acc> acc;
  const auto& vclass = TetMeshBuilder::vertex_class(m_);
  const auto& eclass = TetMeshBuilder::edge_class(m_);
  for (std::size_t r = 0; r < mf_.size(); ++r) {
    Acc& a = acc[key_[r].given];
    ++a.out.facets;
    a.faces.insert(tri_face_[mf_[r]]);
    for (EdgeId e : triangle_edges(m_, TriId(mf_[r])))
      if (eclass[e.idx].dim == 1) a.edges.insert(eclass[e.idx].tag);
    for (VertexId v : m_.triangle(TriId(mf_[r])))
      if (vclass[v.idx].dim == 0) a.corners.insert(vclass[v.idx].tag);
  }
  for (std::size_t ci = 0; ci < cand_.size(); ++ci) {
    if (verdict_[ci] == kNotTested || verdict_[ci] == std::uint8_t(FeatureVerdict::Smooth)) continue;
    MarkerFeatures& o = acc[key_[et_[cand_[ci].t0].r].given].out;
    ++o.sharp_edges;
    const auto v = FeatureVerdict(verdict_[ci]);
    ++(v == FeatureVerdict::Strong ? o.strong_edges : v == FeatureVerdict::Chain ? o.chain_edges : o.noise_edges);
  }
  auto& out = TetMeshBuilder::marker_features(m_);
  for (auto& [marker, a] : acc) {
    if (marker != kNoTag) a.out.marker = marker;
    a.out.model_faces = a.faces.size();
    a.out.model_edges = a.edges.size();
    a.out.corners = a.corners.size();
    out.push_back(a.out);
  }
}

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace

void ClassifyParams::validate() const {
  check_param("ClassifyParams::feature_angle_deg", "degrees",
              ParamRange{kMinFeatureAngleDeg, kMaxFeatureAngleDeg, /*lo_open=*/true}, feature_angle_deg);
  check_param("ClassifyParams::strong_angle_deg", "degrees",
              ParamRange{kMinFeatureAngleDeg, kMaxFeatureAngleDeg, /*lo_open=*/true}, strong_angle_deg);
  check_param("ClassifyParams::min_feature_chain_edges", "edges", ParamRange{1, 1e6}, double(min_feature_chain_edges));
}

Json ClassifyParams::to_json() const {
  Json j = Json::object();
  j.set("feature_angle_deg", feature_angle_deg);
  j.set("strong_angle_deg", strong_angle_deg);
  j.set("min_feature_chain_edges", min_feature_chain_edges);
  return j;
}

Json ClassifyStats::to_json() const {
  Json j = Json::object();
  j.set("validate", seconds_validate);
  j.set("order", seconds_order);
  j.set("topology", seconds_topology);
  j.set("overlap", seconds_overlap);
  j.set("classification", seconds_classification);
  Json out = Json::object();
  out.set("seconds", j);
  return out;
}

namespace {
// ModelEntity::planar of every model face: all its triangles in the plane of
// its first one, by the exact orientation test.
void mark_planar_faces(ClassifiedTetMesh& m) {
  std::map<std::int32_t, std::array<Point3, 3>> plane;  // model face tag -> its first triangle
  std::set<std::int32_t> curved;
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    if (!m.on_model_face(TriId(t))) continue;
    const std::int32_t tag = m.triangle_class(TriId(t)).tag;
    const auto tv = m.triangle(TriId(t));
    const std::array<Point3, 3> tri{m.point(tv[0]), m.point(tv[1]), m.point(tv[2])};
    const auto& ref = plane.try_emplace(tag, tri).first->second;
    for (const Point3& p : tri)
      if (orient3d(ref[0], ref[1], ref[2], p) != Sign::Zero) curved.insert(tag);
  }
  for (ModelEntity& f : TetMeshBuilder::model(m).entities[2]) f.planar = plane.count(f.tag) && !curved.count(f.tag);
}

}  // namespace

ClassifiedTetMesh classify(const TetSoup& soup, const ClassifyParams& params, ClassifyStats* stats) {
  params.validate();
  ClassifyStats local;
  ClassifyStats& st = stats ? *stats : local;
  Compacted c = validate_and_compact(soup, st);
  auto t0 = Clock::now();
  ClassifiedTetMesh m = TetMeshBuilder::build_topology(soup.source, std::move(c.points), std::move(c.tets),
                                                       std::move(c.regions), std::move(c.input_vertex),
                                                       std::move(c.input_tet));
  st.seconds_topology = since(t0);
  if (c.flipped > 0)
    TetMeshBuilder::classification_warnings(m).push_back(
        soup.source + ": all " + std::to_string(c.flipped) + (c.flipped == 1 ? " tet is" : " tets are") +
        " negatively oriented (the producer's convention): flipped");
  t0 = Clock::now();
  check_self_overlap(m);
  st.seconds_overlap = since(t0);
  t0 = Clock::now();
  ModelInference(soup, params, c.remap, m).run();
  mark_planar_faces(m);
  st.seconds_classification = since(t0);
  return m;
}

}  // namespace polydual
