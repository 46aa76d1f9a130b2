// Classification (SPEC §3). The model entities are found bottom-up from the
// mesh: model-face triangles -> model faces (connected pieces, split by given
// tags, region pairs and, when no tag was given, the feature angle); primal
// edges where the model-face triangles do not form one smooth manifold sheet ->
// model edges; vertices where model edges end, branch or bend -> model vertices.
// Every decision here is combinatorial except the feature-angle tests, which are
// plain double geometry (an angle threshold is a modelling choice, not a sign
// that must be exact). Tet orientation is decided exactly (lib/predicates).
#include "classify/classify.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <span>
#include <unordered_map>

#include "classify/spatial_order.h"
#include "classify/union_find.h"
#include "core/radix_sort.h"
#include "core/error.h"
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
};

Compacted validate_and_compact(const TetSoup& s, ClassifyStats& st) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const std::size_t nv = s.points.size();
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
  for (std::size_t v = 0; v < nv; ++v)
    if (used[v] && !is_finite(s.points[v]))
      throw InputError(s.source, "vertex " + std::to_string(v + 1), "coordinate is not finite");
  st.seconds_validate = std::chrono::duration<double>(Clock::now() - t0).count();
  const auto t1 = Clock::now();
  // Spatial order: used vertices along the Morton curve, tets by smallest vertex.
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
  st.seconds_order = std::chrono::duration<double>(Clock::now() - t1).count();
  // EXACT: the orientation of every tet, checked in the new (cache-friendly)
  // order; on a failure, the first failing tet in input order is reported.
  const auto t2 = Clock::now();
  auto orientation_error = [&](std::size_t t) {
    const auto& tv = s.tets[t];
    const Sign o = orient3d(s.points[tv[0]], s.points[tv[1]], s.points[tv[2]], s.points[tv[3]]);
    if (o == Sign::Negative)
      throw InputError(s.source, "tet " + std::to_string(t + 1),
                       "tet " + std::to_string(t + 1) + " is inverted (negative orientation)");
    if (o == Sign::Zero)
      throw InputError(s.source, "tet " + std::to_string(t + 1),
                       "tet " + std::to_string(t + 1) + " has zero volume (degenerate)");
  };
  for (const auto& tv : c.tets)
    if (orient3d(c.points[tv[0].idx], c.points[tv[1].idx], c.points[tv[2].idx], c.points[tv[3].idx]) !=
        Sign::Positive)
      for (std::size_t t = 0; t < s.tets.size(); ++t) orientation_error(t);
  st.seconds_validate += std::chrono::duration<double>(Clock::now() - t2).count();
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

// Bend angle (degrees) between two triangles sharing edge (a,b) with third
// vertices c1, c2: 0 when they continue each other in a plane. Inexact (double).
double bend_angle(const Point3& a, const Point3& b, const Point3& c1, const Point3& c2) {
  Vec3 e = b - a;
  Vec3 n1 = cross(e, c1 - a), n2 = cross(c2 - a, e);
  double d = norm(n1) * norm(n2);
  if (d == 0) return 180.0;
  double cs = std::clamp(dot(n1, n2) / d, -1.0, 1.0);
  return std::acos(cs) * 180.0 / M_PI;
}

VertexId third_vertex(const ClassifiedTetMesh& m, TriId f, EdgeId e) {
  for (VertexId v : m.triangle(f))
    if (v != m.edge(e)[0] && v != m.edge(e)[1]) return v;
  return VertexId::invalid();
}

// Assign tags to components: the first component carrying a given tag keeps it,
// every other component gets a fresh tag above all given ones, in component order.
std::vector<std::int32_t> assign_tags(const std::vector<std::int32_t>& given_tag_of_component,
                                      std::int32_t /*max_given*/) {
  // Fresh tags are the smallest positive integers no component was given, so
  // a given tag of INT32_MAX cannot make them overflow.
  std::set<std::int32_t> given(given_tag_of_component.begin(), given_tag_of_component.end());
  std::set<std::int32_t> used;
  std::vector<std::int32_t> out(given_tag_of_component.size());
  std::int32_t next = 1;
  for (std::size_t c = 0; c < out.size(); ++c) {
    std::int32_t g = given_tag_of_component[c];
    if (g != kNoTag && used.insert(g).second) {
      out[c] = g;
      continue;
    }
    while (given.count(next)) ++next;
    out[c] = next++;
  }
  return out;
}

}  // namespace

ClassifiedTetMesh classify(const TetSoup& soup, const ClassifyParams& params, ClassifyStats* stats) {
  if (!(params.feature_angle_deg > 0 && params.feature_angle_deg <= 180))
    throw UsageError("--feature-angle must be in (0, 180] degrees");
  ClassifyStats local;
  ClassifyStats& st = stats ? *stats : local;
  using Clock = std::chrono::steady_clock;
  auto since = [](Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  auto t0 = Clock::now();
  Compacted c = validate_and_compact(soup, st);
  t0 = Clock::now();
  ClassifiedTetMesh m = TetMeshBuilder::build_topology(soup.source, std::move(c.points), std::move(c.tets),
                                                       std::move(c.regions), std::move(c.input_vertex),
                                                       std::move(c.input_tet));
  st.seconds_topology = since(t0);
  t0 = Clock::now();
  const std::size_t nf = m.num_triangles(), ne = m.num_edges(), nv = m.num_vertices();
  auto remap = [&](std::uint32_t v, const char* what, std::size_t i) {
    if (v >= c.remap.size() || c.remap[v] == std::uint32_t(-1))
      throw InputError(soup.source, std::string(what) + " " + std::to_string(i + 1),
                       "vertex index " + std::to_string(v + 1) + " is out of range or used by no tet");
    return VertexId(c.remap[v]);
  };

  // Everything below works on sparse lists: the model-face triangles (a few
  // per cent of all triangles) and the candidate model edges (edges with a
  // model-face triangle or a given tag), in increasing id order, so the
  // components and tags come out in the same order as a pass over all ids.

  // ---- given triangle tags (dense, looked up by triangle; none: no array)
  std::vector<std::int32_t> tri_given;
  auto given_of = [&](std::size_t f) { return tri_given.empty() ? kNoTag : tri_given[f]; };
  std::int32_t max_face_tag = 0;
  if (!soup.triangles.empty()) tri_given.assign(nf, kNoTag);
  for (std::size_t i = 0; i < soup.triangles.size(); ++i) {
    const auto& t = soup.triangles[i];
    VertexId a = remap(t.v[0], "triangle", i), b = remap(t.v[1], "triangle", i),
             cc = remap(t.v[2], "triangle", i);
    if (a == b || b == cc || a == cc)
      throw InputError(soup.source, "triangle " + std::to_string(i + 1),
                       "triangle " + vlist({t.v[0], t.v[1], t.v[2]}) + " repeats a vertex");
    TriId f = find_triangle(m, a, b, cc);
    if (!f.valid())
      throw InputError(soup.source, "triangle " + std::to_string(i + 1),
                       "triangle " + vlist({t.v[0], t.v[1], t.v[2]}) + " is not a face of any tet");
    if (tri_given[f.idx] != kNoTag && tri_given[f.idx] != t.tag)
      throw InputError(soup.source, "triangle " + std::to_string(i + 1),
                       "triangle classified on two model faces (" + std::to_string(tri_given[f.idx]) +
                           " and " + std::to_string(t.tag) + ")");
    tri_given[f.idx] = t.tag;
    max_face_tag = std::max(max_face_tag, t.tag);
  }

  // ---- model-face triangles (mf[r]: the triangle of rank r) and their grouping key
  struct FaceKey {
    std::int32_t given, r0, r1;  // r1 = kNoTag on the external boundary
    auto operator<=>(const FaceKey&) const = default;
  };
  std::vector<std::uint32_t> mf;
  std::vector<FaceKey> key;  // by rank
  for (std::size_t f = 0; f < nf; ++f) {
    TetId t0 = m.triangle_tet(TriId(f), 0), t1 = m.triangle_tet(TriId(f), 1);
    std::int32_t r0 = m.region(t0), r1 = t1.valid() ? m.region(t1) : kNoTag;
    bool topo = !t1.valid() || r0 != r1;
    const std::int32_t given = given_of(f);
    if (!topo && given == kNoTag) continue;
    if (topo && soup.full_classification && given == kNoTag) {
      const auto& v = m.triangle(TriId(f));
      throw InputError(soup.source, "triangle " + vlist({m.input_vertex(v[0]), m.input_vertex(v[1]), m.input_vertex(v[2])}),
                       std::string("contradiction: the triangle lies ") +
                           (t1.valid() ? "between regions " + std::to_string(r0) + " and " + std::to_string(r1)
                                       : "on the external boundary") +
                           " but the file classifies it on no model face");
    }
    if (r1 != kNoTag && r1 < r0) std::swap(r0, r1);
    mf.push_back(std::uint32_t(f));
    key.push_back({given, r0, r1});
  }
  const std::size_t nmf = mf.size();

  // ---- candidate edges: (edge, rank) incidences sorted by edge (ranks
  // increasing within an edge), merged with the given edges.
  struct EdgeTri { std::uint32_t e, r; };
  std::vector<EdgeTri> et;
  et.reserve(3 * nmf);
  for (std::size_t r = 0; r < nmf; ++r)
    for (EdgeId e : triangle_edges(m, TriId(mf[r]))) et.push_back({e.idx, std::uint32_t(r)});
  // Stable by edge: records were made in rank order, so ranks stay increasing.
  radix_sort_by_key(et, [](const EdgeTri& x) { return x.e; }, std::bit_width(ne));
  std::vector<std::pair<std::uint32_t, std::int32_t>> given_edges;  // (edge, tag), the last given wins
  std::int32_t max_edge_tag = 0;
  for (std::size_t i = 0; i < soup.edges.size(); ++i) {
    VertexId a = remap(soup.edges[i].v[0], "edge", i), b = remap(soup.edges[i].v[1], "edge", i);
    if (a == b)
      throw InputError(soup.source, "edge " + std::to_string(i + 1), "edge repeats a vertex");
    EdgeId e = m.find_edge(a, b);
    if (!e.valid())
      throw InputError(soup.source, "edge " + std::to_string(i + 1),
                       "edge " + vlist({soup.edges[i].v[0], soup.edges[i].v[1]}) + " is not an edge of any tet");
    given_edges.emplace_back(e.idx, soup.edges[i].tag);
    max_edge_tag = std::max(max_edge_tag, soup.edges[i].tag);
  }
  std::stable_sort(given_edges.begin(), given_edges.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  struct Cand {
    std::uint32_t e, t0, t1;  // the edge; its model-face triangles are et[t0 .. t1)
    std::int32_t given;       // given model-edge tag or kNoTag
  };
  std::vector<Cand> cand;
  {
    std::size_t i = 0, g = 0;
    while (i < et.size() || g < given_edges.size()) {
      const std::uint32_t e = std::min(i < et.size() ? et[i].e : UINT32_MAX,
                                       g < given_edges.size() ? given_edges[g].first : UINT32_MAX);
      Cand c{e, std::uint32_t(i), std::uint32_t(i), kNoTag};
      while (i < et.size() && et[i].e == e) ++i;
      c.t1 = std::uint32_t(i);
      while (g < given_edges.size() && given_edges[g].first == e) c.given = given_edges[g++].second;
      cand.push_back(c);
    }
  }
  const std::size_t nc = cand.size();

  // ---- model faces: union across edges with exactly two model-face triangles
  UnionFind uf(nmf);
  for (const Cand& c : cand) {
    if (c.t1 - c.t0 != 2) continue;
    const std::uint32_t f1 = et[c.t0].r, f2 = et[c.t0 + 1].r;
    if (!(key[f1] == key[f2])) continue;
    if (key[f1].given == kNoTag) {
      const auto ev = m.edge(EdgeId(c.e));
      double ang = bend_angle(m.point(ev[0]), m.point(ev[1]), m.point(third_vertex(m, TriId(mf[f1]), EdgeId(c.e))),
                              m.point(third_vertex(m, TriId(mf[f2]), EdgeId(c.e))));
      if (ang > params.feature_angle_deg) continue;
    }
    uf.unite(f1, f2);
  }
  std::vector<std::int32_t> comp_of(nmf, -1), comp_given;
  std::vector<std::uint32_t> root_comp(nmf, std::uint32_t(-1));
  for (std::size_t r = 0; r < nmf; ++r) {
    const std::uint32_t root = uf.find(r);
    if (root_comp[root] == std::uint32_t(-1)) {
      root_comp[root] = std::uint32_t(comp_given.size());
      comp_given.push_back(key[r].given);
    }
    comp_of[r] = std::int32_t(root_comp[root]);
  }
  std::vector<std::int32_t> face_tag = assign_tags(comp_given, max_face_tag);
  auto& tri_face = TetMeshBuilder::triangle_face(m);
  for (std::size_t r = 0; r < nmf; ++r) tri_face[mf[r]] = face_tag[comp_of[r]];

  // ---- model edges
  std::vector<char> is_me(nc, 0);
  // Distinct model-face tags around a candidate edge, computed on demand.
  auto edge_faces = [&](std::size_t ci) {
    std::vector<std::int32_t> tags;
    for (std::uint32_t k = cand[ci].t0; k < cand[ci].t1; ++k) tags.push_back(tri_face[mf[et[k].r]]);
    std::sort(tags.begin(), tags.end());
    tags.erase(std::unique(tags.begin(), tags.end()), tags.end());
    return tags;
  };
  for (std::size_t ci = 0; ci < nc; ++ci) {
    const std::uint32_t n = cand[ci].t1 - cand[ci].t0;
    const std::vector<std::int32_t> tags = n > 0 ? edge_faces(ci) : std::vector<std::int32_t>{};
    bool topo = n > 0 && (n != 2 || tags.size() >= 2);
    if (topo && soup.full_classification && !soup.edges.empty() && cand[ci].given == kNoTag) {
      const auto v = m.edge(EdgeId(cand[ci].e));
      throw InputError(soup.source, "edge " + vlist({m.input_vertex(v[0]), m.input_vertex(v[1])}),
                       "contradiction: model faces meet at this edge but the file classifies it on no model edge");
    }
    is_me[ci] = topo || cand[ci].given != kNoTag;
  }
  // Per-vertex incident model edges (CSR of candidate indices, increasing).
  std::vector<std::uint32_t> vme_off(nv + 1, 0), vme;
  for (std::size_t ci = 0; ci < nc; ++ci)
    if (is_me[ci])
      for (VertexId v : m.edge(EdgeId(cand[ci].e))) ++vme_off[v.idx + 1];
  std::partial_sum(vme_off.begin(), vme_off.end(), vme_off.begin());
  vme.resize(vme_off[nv]);
  {
    std::vector<std::uint32_t> fill(vme_off.begin(), vme_off.end() - 1);
    for (std::size_t ci = 0; ci < nc; ++ci)
      if (is_me[ci])
        for (VertexId v : m.edge(EdgeId(cand[ci].e))) vme[fill[v.idx]++] = std::uint32_t(ci);
  }
  auto v_me = [&](std::size_t v) { return std::span<const std::uint32_t>(vme.data() + vme_off[v], vme.data() + vme_off[v + 1]); };
  auto edge_key = [&](std::uint32_t ci) { return std::make_pair(cand[ci].given, edge_faces(ci)); };

  // ---- model vertices
  std::vector<std::int32_t> corner_given(nv, kNoTag);
  std::int32_t max_vertex_tag = 0;
  for (std::size_t i = 0; i < soup.corners.size(); ++i) {
    VertexId v = remap(soup.corners[i].v, "corner", i);
    corner_given[v.idx] = soup.corners[i].tag;
    max_vertex_tag = std::max(max_vertex_tag, soup.corners[i].tag);
  }
  std::vector<char> is_mv(nv, 0);
  // Distinct model faces at each vertex (for vertices where faces touch without an edge).
  std::vector<std::int32_t> v_face(nv, kNoTag);
  std::vector<char> v_multi_face(nv, 0);
  for (std::size_t r = 0; r < nmf; ++r) {
    const std::int32_t t = tri_face[mf[r]];
    for (VertexId v : m.triangle(TriId(mf[r]))) {
      if (v_face[v.idx] == kNoTag) v_face[v.idx] = t;
      else if (v_face[v.idx] != t) v_multi_face[v.idx] = 1;
    }
  }
  for (std::size_t v = 0; v < nv; ++v) {
    const auto es = v_me(v);
    bool mv = corner_given[v] != kNoTag;
    if (es.empty()) {
      mv = mv || v_multi_face[v];
    } else if (es.size() != 2 || edge_key(es[0]) != edge_key(es[1])) {
      mv = true;
    } else if (cand[es[0]].given == kNoTag) {
      // Sharp corner between two model-edge segments (double geometry).
      const auto e0 = m.edge(EdgeId(cand[es[0]].e)), e1 = m.edge(EdgeId(cand[es[1]].e));
      VertexId a = e0[0] == VertexId(v) ? e0[1] : e0[0];
      VertexId b = e1[0] == VertexId(v) ? e1[1] : e1[0];
      Vec3 d1 = m.point(VertexId(v)) - m.point(a), d2 = m.point(b) - m.point(VertexId(v));
      double cs = dot(d1, d2) / (norm(d1) * norm(d2));
      if (std::acos(std::clamp(cs, -1.0, 1.0)) * 180.0 / M_PI > params.feature_angle_deg) mv = true;
    }
    is_mv[v] = mv;
  }
  // Model edges: components of model-edge primal edges with equal keys, joined
  // at vertices that are not model vertices.
  UnionFind ue(nc);
  for (std::size_t v = 0; v < nv; ++v)
    if (!is_mv[v] && v_me(v).size() == 2) ue.unite(v_me(v)[0], v_me(v)[1]);
  std::vector<std::int32_t> ecomp(nc, -1), ecomp_given;
  std::vector<std::uint32_t> eroot(nc, std::uint32_t(-1));
  for (std::size_t ci = 0; ci < nc; ++ci) {
    if (!is_me[ci]) continue;
    std::uint32_t r = ue.find(ci);
    if (eroot[r] == std::uint32_t(-1)) {
      eroot[r] = std::uint32_t(ecomp_given.size());
      ecomp_given.push_back(cand[ci].given);
    }
    ecomp[ci] = std::int32_t(eroot[r]);
  }
  std::vector<std::int32_t> edge_tag = assign_tags(ecomp_given, max_edge_tag);
  auto& edge_class = TetMeshBuilder::edge_class(m);
  // An edge with no model-face triangle lies in one region: any of its tets.
  for (std::size_t e = 0; e < ne; ++e) edge_class[e] = ModelRef{3, m.region(m.edge_tet(EdgeId(e)))};
  for (std::size_t ci = 0; ci < nc; ++ci) {
    if (is_me[ci])
      edge_class[cand[ci].e] = ModelRef{1, edge_tag[ecomp[ci]]};
    else if (cand[ci].t1 > cand[ci].t0)
      edge_class[cand[ci].e] = ModelRef{2, tri_face[mf[et[cand[ci].t0].r]]};
  }
  std::vector<std::int32_t> vgiven;
  std::vector<std::uint32_t> mv_list;
  for (std::size_t v = 0; v < nv; ++v)
    if (is_mv[v]) { mv_list.push_back(std::uint32_t(v)); vgiven.push_back(corner_given[v]); }
  std::vector<std::int32_t> vtag = assign_tags(vgiven, max_vertex_tag);
  auto& vclass = TetMeshBuilder::vertex_class(m);
  for (std::size_t i = 0; i < mv_list.size(); ++i) vclass[mv_list[i]] = ModelRef{0, vtag[i]};
  for (std::size_t v = 0; v < nv; ++v) {
    if (is_mv[v]) continue;
    if (!v_me(v).empty()) vclass[v] = edge_class[cand[v_me(v)[0]].e];
    else if (v_face[v] != kNoTag) vclass[v] = ModelRef{2, v_face[v]};
    else vclass[v] = ModelRef{3, m.region(m.vertex_tets(VertexId(v)).front())};
  }

  // ---- model topology
  ModelTopology& topo = TetMeshBuilder::model(m);
  std::map<std::int32_t, ModelEntity> regions, faces, edges, verts;
  for (std::size_t t = 0; t < m.num_tets(); ++t) {
    const std::int32_t tag = m.region(TetId(t));
    if (t > 0 && tag == m.region(TetId(t - 1))) continue;  // runs of one region: skip the map
    auto& r = regions[tag];
    r.dim = 3;
    r.tag = tag;
  }
  for (std::size_t r = 0; r < nmf; ++r) {
    auto& e = faces[tri_face[mf[r]]];
    if (e.regions.empty()) {
      e.dim = 2;
      e.tag = tri_face[mf[r]];
      e.regions.push_back(key[r].r0);
      if (key[r].r1 != kNoTag) e.regions.push_back(key[r].r1);
      e.bounds = e.regions;
      e.bounds.erase(std::unique(e.bounds.begin(), e.bounds.end()), e.bounds.end());
    }
  }
  for (std::size_t ci = 0; ci < nc; ++ci) {
    if (!is_me[ci]) continue;
    auto& me = edges[edge_class[cand[ci].e].tag];
    me.dim = 1;
    me.tag = edge_class[cand[ci].e].tag;
    const std::vector<std::int32_t> tags = edge_faces(ci);
    me.bounds.insert(me.bounds.end(), tags.begin(), tags.end());
  }
  for (std::size_t v = 0; v < nv; ++v) {
    if (!is_mv[v]) continue;
    auto& mv = verts[vclass[v].tag];
    mv.dim = 0;
    mv.tag = vclass[v].tag;
    for (std::uint32_t ci : v_me(v)) mv.bounds.push_back(edge_class[cand[ci].e].tag);
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
  st.seconds_classification = since(t0);
  return m;
}

}  // namespace polydual
