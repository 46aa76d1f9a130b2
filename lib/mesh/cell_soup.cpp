// The cell soup of a tet soup, and the counts that name a mixed mesh.
#include "mesh/cell_soup.h"

namespace polydual {

std::array<std::size_t, kNumCellTypes> mixed_cell_counts(const TetSoup& soup) {
  std::array<std::size_t, kNumCellTypes> n{};
  n[std::size_t(CellType::Tet)] = soup.tets.size();
  for (const SoupCell& c : soup.other_cells) ++n[std::size_t(c.type)];
  if (soup.tets.empty() && soup.other_cells.empty()) {
    n[std::size_t(CellType::Triangle)] = soup.triangles.size();
    n[std::size_t(CellType::Quad)] = soup.quads.size();
  }
  return n;
}

bool is_mixed_or_surface(const TetSoup& soup) {
  return !soup.other_cells.empty() || (soup.tets.empty() && !(soup.triangles.empty() && soup.quads.empty()));
}

std::string describe_cell_counts(const std::array<std::size_t, kNumCellTypes>& counts) {
  std::string out;
  for (int t = 0; t < kNumCellTypes; ++t) {
    if (counts[t] == 0) continue;
    const CellDescriptor& d = descriptor(CellType(t));
    if (!out.empty()) out += ", ";
    out += std::to_string(counts[t]) + " " + std::string(counts[t] == 1 ? d.name : d.plural);
  }
  return out.empty() ? "no cells" : out;
}

CellSoup cell_soup(const TetSoup& soup) {
  CellSoup s;
  s.source = soup.source;
  s.points = soup.points;
  s.edges = soup.edges;
  s.corners = soup.corners;
  const bool volume = !soup.tets.empty() || !soup.other_cells.empty();
  if (volume) {
    for (std::size_t t = 0; t < soup.tets.size(); ++t) s.add_cell(CellType::Tet, soup.tets[t], soup.tet_region[t]);
    for (const SoupCell& c : soup.other_cells)
      s.add_cell(c.type, std::span(c.v.data(), std::size_t(descriptor(c.type).num_vertices)), c.region, c.element);
    for (const TaggedTriangle& f : soup.triangles) s.faces.push_back({{f.v[0], f.v[1], f.v[2], 0}, 3, f.tag});
    for (const TaggedQuad& f : soup.quads) s.faces.push_back({f.v, 4, f.tag});
  } else {
    for (const TaggedTriangle& f : soup.triangles) s.add_cell(CellType::Triangle, f.v, f.tag);
    for (const TaggedQuad& f : soup.quads) s.add_cell(CellType::Quad, f.v, f.tag);
  }
  return s;
}

std::string cell_place(const CellSoup& soup, std::size_t c) {
  std::size_t k = 0;
  for (std::size_t i = 0; i < c; ++i) k += soup.cell_type[i] == soup.cell_type[c];
  std::string out = std::string(descriptor(soup.cell_type[c]).name) + " " + std::to_string(k + 1);
  if (c < soup.cell_element.size() && soup.cell_element[c] != 0)
    out += " (element " + std::to_string(soup.cell_element[c]) + ")";
  return out;
}

}  // namespace polydual
