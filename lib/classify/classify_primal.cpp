// Exact orientation of mixed cells, then PrimalMeshBuilder.
#include "classify/classify_primal.h"

#include "core/error.h"
#include "predicates/predicates.h"

namespace polydual {
namespace {

// +1: every corner tet positive; -1: every one negative; 0 otherwise (a zero
// or mixed sign: degenerate or twisted). EXACT (orient3d). `corner` receives
// the first corner that is neither.
int cell_orientation(const CellSoup& s, std::size_t c, int& corner) {
  const CellDescriptor& d = descriptor(s.cell_type[c]);
  const auto v = s.cell(c);
  int pos = 0, neg = 0;
  corner = -1;
  for (int k = 0; k < d.num_corners; ++k) {
    const auto& q = d.corners[k];
    const Sign o = orient3d(s.points[v[q[0]]], s.points[v[q[1]]], s.points[v[q[2]]], s.points[v[q[3]]]);
    pos += o == Sign::Positive;
    neg += o == Sign::Negative;
    if (o != Sign::Positive && corner < 0) corner = k;
  }
  return pos == d.num_corners ? 1 : neg == d.num_corners ? -1 : 0;
}

void mirror(CellSoup& s, std::size_t c) {
  const CellDescriptor& d = descriptor(s.cell_type[c]);
  std::uint32_t* v = s.cell_vertex.data() + s.cell_offset[c];
  std::array<std::uint32_t, 8> old{};
  std::copy(v, v + d.num_vertices, old.begin());
  for (int i = 0; i < d.num_vertices; ++i) v[i] = old[d.mirror[i]];
}

// A surface cell (triangle, quadrangle) with three consecutive corners on one
// line has no normal: an InputError naming it. EXACT: collinear iff orient2d
// is zero on all three coordinate projections (dropping a coordinate is exact).
void check_surface_cell(const CellSoup& s, std::size_t c) {
  const auto v = s.cell(c);
  for (std::size_t k = 0; k < (v.size() == 3 ? 1 : v.size()); ++k) {
    const Point3 &a = s.points[v[k]], &b = s.points[v[(k + 1) % v.size()]], &d = s.points[v[(k + 2) % v.size()]];
    if (orient2d(a.x, a.y, b.x, b.y, d.x, d.y) == Sign::Zero && orient2d(a.y, a.z, b.y, b.z, d.y, d.z) == Sign::Zero &&
        orient2d(a.z, a.x, b.z, b.x, d.z, d.x) == Sign::Zero)
      throw InputError(s.source, cell_place(s, c),
                       cell_place(s, c) + " is degenerate (its corners " + std::to_string(v[k] + 1) + ", " +
                           std::to_string(v[(k + 1) % v.size()] + 1) + ", " + std::to_string(v[(k + 2) % v.size()] + 1) +
                           " are collinear)");
  }
}

void orient_cells(CellSoup& s, std::vector<std::string>* warnings) {
  std::array<std::size_t, kNumCellTypes> total{}, inverted{};
  std::array<std::size_t, kNumCellTypes> first_inverted{};
  for (std::size_t c = 0; c < s.num_cells(); ++c) {
    const std::size_t t = std::size_t(s.cell_type[c]);
    if (descriptor(s.cell_type[c]).dim != 3) {
      check_surface_cell(s, c);
      continue;
    }
    int corner = -1;
    const int o = cell_orientation(s, c, corner);
    if (o == 0)
      throw InputError(s.source, cell_place(s, c),
                       cell_place(s, c) + " is degenerate or twisted (its corner tet at local vertex " +
                           std::to_string(int(descriptor(s.cell_type[c]).corners[corner][0])) +
                           " is not positively oriented while others are, or has zero volume)");
    if (o < 0 && inverted[t]++ == 0) first_inverted[t] = c;
    ++total[t];
  }
  for (int t = 0; t < kNumCellTypes; ++t) {
    if (inverted[t] == 0) continue;
    if (inverted[t] != total[t])
      throw InputError(s.source, cell_place(s, first_inverted[t]),
                       cell_place(s, first_inverted[t]) + " is inverted (negative orientation) while " +
                           std::to_string(total[t] - inverted[t]) + " " + std::string(descriptor(CellType(t)).plural) +
                           " are positive");
    for (std::size_t c = 0; c < s.num_cells(); ++c)
      if (int(s.cell_type[c]) == t) mirror(s, c);
    if (warnings)
      warnings->push_back(s.source + ": all " + std::to_string(total[t]) + " " +
                          std::string(descriptor(CellType(t)).plural) +
                          " are negatively oriented (the mirror convention); reordered");
  }
}

}  // namespace

PrimalMesh build_primal(CellSoup soup, std::vector<std::string>* warnings) {
  orient_cells(soup, warnings);
  return PrimalMeshBuilder::build(soup);
}

}  // namespace polydual
