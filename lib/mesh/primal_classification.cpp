// PrimalMeshBuilder: the classification of faces, edges and vertices (design
// §14). What the source tagged is kept; the rest is completed by the rule of
// design §3 without the feature-angle split (classify() does that for tet
// meshes): a face with one cell, or between two regions, lies on a model face
// (one per pair of regions); an edge where model faces end, branch or change
// tag lies on a model edge (one per set of model faces meeting there); a
// vertex where model edges end, branch or change tag is a model vertex. In a
// surface mesh the cells play the model faces' part.
#include <algorithm>
#include <map>
#include <set>
#include <unordered_map>

#include "core/error.h"
#include "mesh/cell_soup.h"
#include "mesh/primal_mesh.h"

namespace polydual {
namespace {

std::int32_t next_tag(std::int32_t start, const auto& tagged) {
  for (const auto& t : tagged) start = std::max(start, t.tag);
  return start + 1;
}

// Fresh tags numbered by first occurrence of their key.
template <class Key>
struct FreshTags {
  std::int32_t next;
  std::map<Key, std::int32_t> tags;
  std::int32_t operator()(const Key& k) {
    const auto [it, fresh] = tags.emplace(k, next);
    if (fresh) ++next;
    return it->second;
  }
};

using FaceKey = std::array<std::uint32_t, 4>;

// A tagged triangle or quadrangle of the source that is no face of a cell:
// named by its vertices (1-based) and tag.
[[noreturn]] void unmatched_face_error(const PrimalMesh& m, const CellSoup& soup,
                                       const std::map<FaceKey, std::int32_t>& tag_of, std::size_t matched) {
  std::set<FaceKey> faces;
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    FaceKey k{0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu};
    const auto fv = m.face_vertices(PrimalFaceId(f));
    for (std::size_t i = 0; i < fv.size(); ++i) k[i] = fv[i].idx;
    std::sort(k.begin(), k.end());
    faces.insert(k);
  }
  for (const auto& [k, tag] : tag_of) {
    if (faces.count(k)) continue;
    std::string v;
    for (std::uint32_t x : k)
      if (x != 0xffffffffu) {
        if (!v.empty()) v += ' ';
        v += std::to_string(x + 1);
      }
    throw InputError(soup.source, "face (" + v + ")",
                     "the " + std::string(k[3] == 0xffffffffu ? "triangle" : "quadrangle") + " (" + v + ") tagged " +
                         std::to_string(tag) + " is no face of any cell (" + std::to_string(tag_of.size() - matched) +
                         " such)");
  }
  throw InputError(soup.source, "", "tagged faces do not match the cells");
}

}  // namespace

void PrimalMeshBuilder::classify_faces(PrimalMesh& m, const CellSoup& soup) {
  if (m.dim_ != 3) return;
  std::map<std::array<std::uint32_t, 4>, std::int32_t> tag_of;
  for (std::size_t i = 0; i < soup.faces.size(); ++i) {
    std::array<std::uint32_t, 4> k = soup.faces[i].v;
    if (soup.faces[i].n == 3) k[3] = 0xffffffffu;
    std::sort(k.begin(), k.end());
    tag_of[k] = soup.faces[i].tag;
  }
  FreshTags<std::pair<std::int32_t, std::int32_t>> fresh{next_tag(0, soup.faces), {}};
  std::size_t matched = 0;
  m.face_class_.assign(m.num_faces(), ModelRef{});
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    std::array<std::uint32_t, 4> k{0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu};
    const auto fv = m.face_vertices(PrimalFaceId(f));
    for (std::size_t i = 0; i < fv.size(); ++i) k[i] = fv[i].idx;
    std::sort(k.begin(), k.end());
    const auto [c0, c1] = m.face_cell_[f];
    const std::int32_t r0 = m.cell_region_[c0.idx], r1 = c1.valid() ? m.cell_region_[c1.idx] : r0;
    if (const auto it = tag_of.find(k); it != tag_of.end()) {
      m.face_class_[f] = {2, it->second};
      ++matched;
    } else if (!c1.valid() || r0 != r1) {
      m.face_class_[f] = {2, fresh({std::min(r0, r1), c1.valid() ? std::max(r0, r1) : INT32_MIN})};
    } else {
      m.face_class_[f] = {3, r0};
    }
  }
  if (matched != tag_of.size()) unmatched_face_error(m, soup, tag_of, matched);
}

// Per edge: the model-face (or, in a surface mesh, cell) tags around it and
// how many such faces; the edge's class follows.
void PrimalMeshBuilder::classify_edges(PrimalMesh& m, const CellSoup& soup) {
  std::vector<std::uint32_t> count(m.num_edges(), 0);
  std::vector<std::vector<std::int32_t>> tags(m.num_edges());
  auto note = [&](EdgeId e, std::int32_t tag) {
    ++count[e.idx];
    if (std::find(tags[e.idx].begin(), tags[e.idx].end(), tag) == tags[e.idx].end()) tags[e.idx].push_back(tag);
  };
  if (m.dim_ == 3) {
    for (std::size_t f = 0; f < m.num_faces(); ++f) {
      if (m.face_class_[f].dim != 2) continue;
      const auto fv = m.face_vertices(PrimalFaceId(f));
      for (std::size_t i = 0; i < fv.size(); ++i) note(m.find_edge(fv[i], fv[(i + 1) % fv.size()]), m.face_class_[f].tag);
    }
  } else {
    for (std::size_t e = 0; e < m.num_edges(); ++e)
      for (PrimalCellId c : m.edge_cells(EdgeId(e))) note(EdgeId(e), m.cell_region_[c.idx]);
  }
  std::map<std::pair<VertexId, VertexId>, std::int32_t> given;
  for (const TaggedEdge& e : soup.edges)
    given[{VertexId(std::min(e.v[0], e.v[1])), VertexId(std::max(e.v[0], e.v[1]))}] = e.tag;
  FreshTags<std::vector<std::int32_t>> fresh{next_tag(0, soup.edges), {}};
  m.edge_class_.assign(m.num_edges(), ModelRef{});
  for (std::size_t e = 0; e < m.num_edges(); ++e) {
    const auto [a, b] = m.edge_vertex_[e];
    std::sort(tags[e].begin(), tags[e].end());
    if (const auto it = given.find({a, b}); it != given.end())
      m.edge_class_[e] = {1, it->second};
    else if (count[e] == 0)
      m.edge_class_[e] = {3, m.cell_region_[m.edge_cells(EdgeId(e))[0].idx]};
    else if (count[e] == 2 && tags[e].size() == 1)
      m.edge_class_[e] = {2, tags[e][0]};
    else
      m.edge_class_[e] = {1, fresh(tags[e])};
  }
}

void PrimalMeshBuilder::classify_vertices(PrimalMesh& m, const CellSoup& soup) {
  // Per vertex: model edges at it and their distinct tags (-1: several), and
  // a model face tag at it (-1: several).
  struct At {
    std::uint32_t edges = 0;
    std::int64_t edge_tag = INT64_MIN, face_tag = INT64_MIN;
  };
  constexpr std::int64_t kNone = INT64_MIN, kSeveral = INT64_MIN + 1;
  std::vector<At> at(m.num_vertices());
  auto merge = [&](std::int64_t& slot, std::int32_t tag) { slot = slot == kNone || slot == tag ? tag : kSeveral; };
  for (std::size_t e = 0; e < m.num_edges(); ++e)
    for (VertexId v : m.edge_vertex_[e]) {
      const ModelRef c = m.edge_class_[e];
      if (c.dim == 1) ++at[v.idx].edges, merge(at[v.idx].edge_tag, c.tag);
      if (c.dim == 2) merge(at[v.idx].face_tag, c.tag);
    }
  std::map<VertexId, std::int32_t> given;
  for (const TaggedVertex& c : soup.corners) given[VertexId(c.v)] = c.tag;
  std::int32_t fresh = next_tag(0, soup.corners);
  m.vertex_class_.assign(m.num_vertices(), ModelRef{});
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    const At& a = at[v];
    if (m.vstar_off_[v] == m.vstar_off_[v + 1]) continue;  // used by no cell: unclassified
    if (const auto it = given.find(VertexId(v)); it != given.end())
      m.vertex_class_[v] = {0, it->second};
    else if (a.edges != 0 && (a.edges != 2 || a.edge_tag == kSeveral))
      m.vertex_class_[v] = {0, fresh++};
    else if (a.edges == 2)
      m.vertex_class_[v] = {1, std::int32_t(a.edge_tag)};
    else if (a.face_tag == kSeveral)
      m.vertex_class_[v] = {0, fresh++};
    else if (a.face_tag != kNone)
      m.vertex_class_[v] = {2, std::int32_t(a.face_tag)};
    else
      m.vertex_class_[v] = {std::int8_t(m.dim_), m.cell_region_[m.vstar_[m.vstar_off_[v]].idx]};
  }
}

}  // namespace polydual
