// Lattice-triangulated planar fractures (fracture_surfaces.h).
#include "generate/fracture_surfaces.h"

#include <map>

#include "core/error.h"

namespace polydual {
namespace {

bool even(int x) { return x % 2 == 0; }
bool offset_row(int t) { return (t / 2) % 2 != 0; }  // t even; C++ '%' keeps the sign: != 0 covers -1

// The s values of row t of rectangle r.
std::vector<int> row_points(const LatticeRectangle& r, int t) {
  std::vector<int> s;
  if (!offset_row(t)) {
    for (int x = r.s0; x <= r.s1; x += 2) s.push_back(x);
    return s;
  }
  s.push_back(r.s0);
  for (int x = r.s0 + 1; x < r.s1; x += 2) s.push_back(x);
  s.push_back(r.s1);
  return s;
}

struct Builder {
  int n;
  TetSoup soup;
  std::map<std::array<int, 3>, std::uint32_t> index;

  std::uint32_t point(const LatticeRectangle& r, int s, int t) {
    std::array<int, 3> key{};
    key[r.axis] = r.offset;
    key[r.row_axis] = s;
    key[3 - r.axis - r.row_axis] = t;
    const auto [it, fresh] = index.emplace(key, std::uint32_t(soup.points.size()));
    if (fresh) {
      const double u = 1.0 / (2.0 * n);
      soup.points.push_back({key[0] * u, key[1] * u, key[2] * u});
    }
    return it->second;
  }

  // Zips rows t and t + 2 into counterclockwise triangles (in (s, t)).
  void zip(const LatticeRectangle& r, int t) {
    const std::vector<int> lo = row_points(r, t), up = row_points(r, t + 2);
    std::size_t i = 0, k = 0;
    while (i + 1 < lo.size() || k + 1 < up.size()) {
      // The row whose next point comes first advances; at the rows' common
      // end, the one that is behind (else the triangle there is obtuse).
      const bool advance_lo = k + 1 == up.size() || (i + 1 < lo.size() && (lo[i + 1] < up[k + 1] ||
                                                                            (lo[i + 1] == up[k + 1] && lo[i] <= up[k])));
      if (advance_lo) {
        soup.triangles.push_back({{point(r, lo[i], t), point(r, lo[i + 1], t), point(r, up[k], t + 2)}, r.tag});
        ++i;
      } else {
        soup.triangles.push_back({{point(r, lo[i], t), point(r, up[k + 1], t + 2), point(r, up[k], t + 2)}, r.tag});
        ++k;
      }
    }
  }
};

}  // namespace

TetSoup lattice_rectangles_soup(const std::vector<LatticeRectangle>& rects, int n, const std::string& source) {
  if (n < 1) throw UsageError("lattice rectangles: n must be positive (got " + std::to_string(n) + ")");
  Builder b{n, {}, {}};
  b.soup.source = source;
  for (const LatticeRectangle& r : rects) {
    if (r.axis < 0 || r.axis > 2 || r.row_axis < 0 || r.row_axis > 2 || r.row_axis == r.axis || r.s0 >= r.s1 || r.t0 >= r.t1 || !even(r.s0) || !even(r.s1) || !even(r.t0) ||
        !even(r.t1) || !even(r.offset))
      throw UsageError("lattice rectangles: a rectangle off the lattice (axis 0..2, even coordinates, s0 < s1, t0 < t1)");
    for (int t = r.t0; t < r.t1; t += 2) b.zip(r, t);
  }
  return std::move(b.soup);
}

TetSoup fracture_network_surface(int n) {
  if (n < 4 || n % 4 != 0)
    throw UsageError("fracture network surface: n must be a positive multiple of 4 (got " + std::to_string(n) + ")");
  const int one = 2 * n;  // 1.0 in units u
  const std::vector<LatticeRectangle> rects = {
      {2, 0, 0, -one, one, -one, one, 1},                          // F1: z = 0 (s = x, t = y)
      {1, 0, 0, -one, one, -one, one, 2},                          // F2: y = 0 (s = x, t = z)
      {1, one / 2, 0, one / 4, 3 * one / 4, -one / 2, one / 2, 3},  // F3: y = 0.5 (s = x, t = z)
  };
  return lattice_rectangles_soup(rects, n, "<fracture network n=" + std::to_string(n) + ">");
}

}  // namespace polydual
