#include "io/unattached.h"

#include <algorithm>
#include <array>
#include <set>
#include <string>

namespace polydual::io {
namespace {

struct Counts {
  std::size_t unused_vertex = 0, degenerate = 0;
};

// Keeps the elements `keep` accepts (stable), their origins alongside; returns
// the entities that keep an element and, in `all`, every entity seen.
template <class Element, class Keep>
std::set<std::int32_t> filter(std::vector<Element>& elements, const std::vector<std::int32_t>& origin,
                              std::set<std::int32_t>& all, Keep keep) {
  std::set<std::int32_t> kept;
  std::size_t out = 0;
  for (std::size_t i = 0; i < elements.size(); ++i) {
    const std::int32_t entity = origin.empty() ? elements[i].tag : origin[i];
    all.insert(entity);
    if (!keep(elements[i])) continue;
    kept.insert(entity);
    elements[out++] = elements[i];
  }
  elements.resize(out);
  return kept;
}

std::size_t dropped_whole(const std::set<std::int32_t>& all, const std::set<std::int32_t>& kept) {
  std::size_t n = 0;
  for (std::int32_t e : all) n += kept.count(e) == 0;
  return n;
}

void restrict_groups(TetSoup& soup) {
  std::array<std::set<std::int32_t>, 3> carried;
  for (const TaggedVertex& c : soup.corners) carried[0].insert(c.tag);
  for (const TaggedEdge& e : soup.edges) carried[1].insert(e.tag);
  for (const TaggedTriangle& t : soup.triangles) carried[2].insert(t.tag);
  for (NamedGroup& g : soup.groups) {
    if (g.dim > 2) continue;
    std::erase_if(g.entities, [&](std::int32_t e) { return carried[g.dim].count(e) == 0; });
  }
}

// Removes the elements at the marked positions (stable), and the parallel
// entries of `also` when it is not empty.
template <class Element, class Parallel>
void erase_marked(std::vector<Element>& elements, Parallel& also, const std::vector<char>& drop) {
  std::size_t out = 0;
  for (std::size_t i = 0; i < elements.size(); ++i) {
    if (drop[i]) continue;
    if (!also.empty()) also[out] = also[i];
    elements[out++] = elements[i];
  }
  elements.resize(out);
  if (!also.empty()) also.resize(out);
}

// Drops [begin, end) of every run of dimension dim from `elements`.
template <class Element, class Parallel>
std::size_t erase_runs(std::vector<Element>& elements, Parallel& also, const std::vector<ElementRun>& runs, int dim) {
  std::vector<char> drop;
  std::size_t n = 0;
  for (const ElementRun& r : runs) {
    if (r.dim != dim || r.begin >= r.end) continue;
    if (drop.empty()) drop.assign(elements.size(), 0);
    for (std::size_t i = r.begin; i < r.end && i < elements.size(); ++i) n += !drop[i], drop[i] = 1;
  }
  if (n > 0) erase_marked(elements, also, drop);
  return n;
}

}  // namespace

bool is_chain_name(std::string_view name) {
  return name.size() >= 3 && name[0] == 'H' && (name[1] == '_' || name[1] == '^') && name[2] >= '0' && name[2] <= '3';
}

void drop_chains(TetSoup& soup, ElementOrigins& origins, const std::vector<ElementRun>& chains) {
  if (chains.empty()) return;
  std::size_t dropped = erase_runs(soup.tets, soup.tet_region, chains, 3);
  dropped += erase_runs(soup.triangles, origins.triangle, chains, 2);
  dropped += erase_runs(soup.edges, origins.edge, chains, 1);
  dropped += erase_runs(soup.corners, origins.corner, chains, 0);
  std::set<std::pair<int, std::int32_t>> entities, groups;
  for (const ElementRun& r : chains) entities.insert({r.dim, r.entity}), groups.insert({r.dim, r.group});
  std::array<std::size_t, 4> per_dim{};
  for (const auto& [d, e] : entities) ++per_dim[d];
  std::string names;
  std::size_t named = 0;
  std::erase_if(soup.groups, [&](const NamedGroup& g) {
    if (!groups.count({g.dim, g.tag})) return false;
    if (named++ < 6) names += (names.empty() ? "" : ", ") + (g.name.empty() ? std::to_string(g.tag) : g.name);
    return true;
  });
  if (named > 6) names += " and " + std::to_string(named - 6) + " more";
  soup.ignored.points += per_dim[0];
  soup.ignored.curves += per_dim[1];
  soup.ignored.surfaces += per_dim[2];
  soup.ignored.elements += dropped;
  soup.ignored.chains += groups.size();
  std::string w = soup.source + ": ignored " + count_of(groups.size(), "homology or cohomology chain", "homology and cohomology chains") +
                  " (" + names + "; " + count_of(dropped, "element", "elements");
  if (per_dim[3] > 0) w += ", " + count_of(per_dim[3], "volume", "volumes");
  soup.warnings.push_back(w + "): Gmsh's (co)homology results, not model entities");
}

std::string count_of(std::size_t n, const char* singular, const char* plural) {
  return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

void drop_unattached(TetSoup& soup, const ElementOrigins& origins) {
  // No tet has a quadrangular face: a tet mesh's quadrangles (a file that
  // also holds a surface mesh) are ignored, as readers always did.
  if (!soup.tets.empty() && soup.other_cells.empty()) soup.quads.clear();
  std::vector<char> used(soup.points.size(), 0);
  for (const auto& t : soup.tets)
    for (std::uint32_t v : t)
      if (v < used.size()) used[v] = 1;
  // The other volume cells attach as the tets do; a surface mesh (no volume
  // cell) is its triangles and quadrangles.
  for (const SoupCell& c : soup.other_cells)
    for (int k = 0; k < descriptor(c.type).num_vertices; ++k)
      if (c.v[k] < used.size()) used[c.v[k]] = 1;
  if (soup.tets.empty() && soup.other_cells.empty()) {
    for (const auto& t : soup.triangles)
      for (std::uint32_t v : t.v)
        if (v < used.size()) used[v] = 1;
    for (const auto& q : soup.quads)
      for (std::uint32_t v : q.v)
        if (v < used.size()) used[v] = 1;
  }
  auto is_used = [&](std::uint32_t v) { return v < used.size() && used[v]; };
  Counts n;
  std::array<std::set<std::int32_t>, 3> all;
  for (int d = 0; d < 3; ++d) all[d].insert(origins.declared[d].begin(), origins.declared[d].end());
  for (const TaggedQuad& q : soup.quads) all[2].erase(q.tag);  // quadrangles are kept whole
  const std::size_t before = soup.triangles.size() + soup.edges.size() + soup.corners.size();
  const std::set<std::int32_t> kept2 = filter(soup.triangles, origins.triangle, all[2], [&](const TaggedTriangle& t) {
    const bool ok = is_used(t.v[0]) && is_used(t.v[1]) && is_used(t.v[2]);
    n.unused_vertex += !ok;
    return ok;
  });
  const std::set<std::int32_t> kept1 = filter(soup.edges, origins.edge, all[1], [&](const TaggedEdge& e) {
    if (e.v[0] == e.v[1]) return ++n.degenerate, false;
    const bool ok = is_used(e.v[0]) && is_used(e.v[1]);
    n.unused_vertex += !ok;
    return ok;
  });
  const std::set<std::int32_t> kept0 = filter(soup.corners, origins.corner, all[0], [&](const TaggedVertex& c) {
    const bool ok = is_used(c.v);
    n.unused_vertex += !ok;
    return ok;
  });
  const std::size_t dropped = before - (soup.triangles.size() + soup.edges.size() + soup.corners.size());
  IgnoredEntities add;
  add.points = dropped_whole(all[0], kept0);
  add.curves = dropped_whole(all[1], kept1);
  add.surfaces = dropped_whole(all[2], kept2);
  add.elements = dropped;
  soup.ignored.points += add.points;
  soup.ignored.curves += add.curves;
  soup.ignored.surfaces += add.surfaces;
  soup.ignored.elements += add.elements;
  restrict_groups(soup);
  if (!add.any()) return;
  // Nothing dropped: the entities were declared with no element at all
  // (Gmsh declares a sphere's poles as degenerate curves with none).
  std::string w = soup.source + ": ";
  if (dropped > 0)
    w += "ignored " + count_of(dropped, "lower-dimensional element", "lower-dimensional elements") +
         " not attached to the tets (" + std::to_string(n.unused_vertex) + " with a vertex no tet uses, " +
         std::to_string(n.degenerate) + " degenerate with a repeated vertex)" +
         (add.points + add.curves + add.surfaces > 0 ? "; " : "");
  if (add.points + add.curves + add.surfaces > 0)
    w += "model entities with no element on the tets: " + count_of(add.points, "point", "points") + ", " +
         count_of(add.curves, "curve", "curves") + ", " + count_of(add.surfaces, "surface", "surfaces") +
         (dropped == 0 ? " (declared by the file with no element)" : "");
  soup.warnings.push_back(std::move(w));
}

}  // namespace polydual::io
