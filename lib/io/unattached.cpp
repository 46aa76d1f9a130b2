#include "io/unattached.h"

#include <algorithm>
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

}  // namespace

std::string count_of(std::size_t n, const char* singular, const char* plural) {
  return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

void drop_unattached(TetSoup& soup, const ElementOrigins& origins) {
  std::vector<char> used(soup.points.size(), 0);
  for (const auto& t : soup.tets)
    for (std::uint32_t v : t)
      if (v < used.size()) used[v] = 1;
  auto is_used = [&](std::uint32_t v) { return v < used.size() && used[v]; };
  Counts n;
  std::array<std::set<std::int32_t>, 3> all;
  for (int d = 0; d < 3; ++d) all[d].insert(origins.declared[d].begin(), origins.declared[d].end());
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
  std::string w = soup.source + ": ignored " + count_of(dropped, "lower-dimensional element", "lower-dimensional elements") +
                  " not attached to the tets (" + std::to_string(n.unused_vertex) + " with a vertex no tet uses, " +
                  std::to_string(n.degenerate) + " degenerate with a repeated vertex)";
  if (add.points + add.curves + add.surfaces > 0)
    w += "; model entities with no element on the tets: " + count_of(add.points, "point", "points") + ", " +
         count_of(add.curves, "curve", "curves") + ", " + count_of(add.surfaces, "surface", "surfaces");
  soup.warnings.push_back(std::move(w));
}

}  // namespace polydual::io
