// Random mixed meshes (generate/random_mixed.h). Orientation decisions are
// exact (orient3d); the generated coordinates are rounded constructions.
#include "generate/random_mixed.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <stdexcept>

#include "core/error.h"
#include "predicates/predicates.h"

namespace polydual {

namespace {

// As random_mesh.cpp: a double in (0, 1) from the top 53 bits of a draw, the
// same with every standard library.
double open_unit(std::uint64_t bits) { return (static_cast<double>(bits >> 11) + 0.5) * 0x1.0p-53; }

// A boundary face of the soup's volume cells: its outward loop and the
// region of its cell.
struct BoundaryFace {
  std::vector<std::uint32_t> loop;
  std::int32_t region = 0;
};

// The faces of the soup's cells that only one cell has, in the order of
// their sorted vertices.
std::vector<BoundaryFace> boundary_faces(const TetSoup& s) {
  std::map<std::vector<std::uint32_t>, std::pair<int, BoundaryFace>> faces;
  auto visit = [&](CellType t, const std::uint32_t* v, std::int32_t region) {
    const CellDescriptor& d = descriptor(t);
    for (int i = 0; i < d.num_faces; ++i) {
      BoundaryFace f{{}, region};
      for (int k = 0; k < d.face_size[i]; ++k) f.loop.push_back(v[d.faces[i][k]]);
      auto key = f.loop;
      std::sort(key.begin(), key.end());
      auto& e = faces[key];
      ++e.first;
      e.second = std::move(f);
    }
  };
  for (std::size_t t = 0; t < s.tets.size(); ++t) visit(CellType::Tet, s.tets[t].data(), s.tet_region[t]);
  for (const SoupCell& c : s.other_cells) visit(c.type, c.v.data(), c.region);
  std::vector<BoundaryFace> out;
  for (auto& [key, e] : faces)
    if (e.first == 1) out.push_back(std::move(e.second));
  return out;
}

// The outward direction of a point of the unit box's boundary: the sum of
// the outward normals of the box faces it lies on (zero inside).
Point3 box_normal(const Point3& p) {
  Point3 n{0, 0, 0};
  for (int c = 0; c < 3; ++c) n[c] = p[c] == 0.0 ? -1.0 : p[c] == 1.0 ? 1.0 : 0.0;
  return n;
}

}  // namespace

void add_cell(TetSoup& s, CellType t, std::vector<std::uint32_t> v, std::int32_t region) {
  const CellDescriptor& d = descriptor(t);
  const auto& c = d.corners[0];
  const Sign sign = orient3d(s.points[v[c[0]]], s.points[v[c[1]]], s.points[v[c[2]]], s.points[v[c[3]]]);
  if (sign == Sign::Zero) throw std::logic_error("mixed soup: a flat corner of a " + std::string(d.name));
  if (sign == Sign::Negative) {
    std::vector<std::uint32_t> w(v.size());
    for (std::size_t k = 0; k < v.size(); ++k) w[k] = v[std::size_t(d.mirror[k])];
    v = std::move(w);
  }
  if (t == CellType::Tet) {
    s.tets.push_back({v[0], v[1], v[2], v[3]});
    s.tet_region.push_back(region);
    return;
  }
  SoupCell cell;
  cell.type = t;
  std::copy(v.begin(), v.end(), cell.v.begin());
  cell.region = region;
  s.other_cells.push_back(cell);
}

void tag_box_boundary(TetSoup& s, double lo, double hi) {
  for (const BoundaryFace& f : boundary_faces(s)) {
    int side = 0;
    for (int d = 0; d < 3 && !side; ++d)
      for (double x : {lo, hi})
        if (std::all_of(f.loop.begin(), f.loop.end(), [&](std::uint32_t v) { return s.points[v][d] == x; }))
          side = 2 * d + (x == hi) + 1;
    if (!side) continue;
    const auto& l = f.loop;
    if (l.size() == 3) s.triangles.push_back({{l[0], l[1], l[2]}, side});
    else s.quads.push_back({{l[0], l[1], l[2], l[3]}, side});
  }
}

TetSoup random_prism_layers(const RandomMeshParams& tets, int layers, double first, double ratio) {
  if (layers < 1 || !(first > 0) || !(ratio > 0))
    throw UsageError("prism layers need layers >= 1, first > 0 and ratio > 0");
  if (tets.notch || tets.touching || tets.unattached)
    throw UsageError("prism layers grow on the unit box: no notch, touching blocks or unattached entities");
  TetSoup s = random_classified_mesh(tets);
  s.source = "<random prism layers>";
  // Layer k of boundary point v: index layer_of[v] + k - 1 (k >= 1).
  std::vector<std::uint32_t> layer_of(s.points.size(), 0);
  const std::vector<BoundaryFace> faces = boundary_faces(s);
  std::vector<double> height{0};
  for (int k = 0; k < layers; ++k) height.push_back(height.back() + first * std::pow(ratio, k));
  for (const BoundaryFace& f : faces)
    for (std::uint32_t v : f.loop) {
      if (layer_of[v]) continue;
      const Point3 p = s.points[v], n = box_normal(p);
      if (n == Point3{0, 0, 0}) throw std::logic_error("prism layers: a boundary point off the unit box");
      layer_of[v] = std::uint32_t(s.points.size());
      for (int k = 1; k <= layers; ++k) s.points.push_back(p + n * height[std::size_t(k)]);
    }
  auto at = [&](std::uint32_t v, int k) { return k == 0 ? v : layer_of[v] + std::uint32_t(k - 1); };
  // The face's outward loop (a, b, c) turns about the outward direction, so
  // (a_k, b_k, c_k, a_k+1, ...) is a positive prism (add_cell checks it).
  for (const BoundaryFace& f : faces)
    for (int k = 0; k < layers; ++k) {
      std::vector<std::uint32_t> v;
      for (int z = 0; z < 2; ++z)
        for (std::uint32_t x : f.loop) v.push_back(at(x, k + z));
      add_cell(s, CellType::Prism, v, f.region);
    }
  tag_box_boundary(s, -height.back(), 1 + height.back());
  return s;
}

TetSoup random_hex_pyramid_tets(std::uint64_t seed, int n, double jitter) {
  if (n < 2 || n % 2 != 0 || !(jitter >= 0 && jitter < 0.5))
    throw UsageError("hex-pyramid-tet block needs an even n >= 2 and 0 <= jitter < 1/2");
  TetSoup s;
  s.source = "<random hex-pyramid-tet block>";
  auto id = [n](int i, int j, int k) { return std::uint32_t((k * (n + 1) + j) * (n + 1) + i); };
  std::mt19937_64 rng(seed);
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const int index[3] = {i, j, k};
        Point3 p{double(i) / n, double(j) / n, double(k) / n};
        for (int c = 0; c < 3; ++c) {
          const double u = open_unit(rng());  // drawn for every coordinate: same stream for any jitter
          const bool fixed = index[c] == 0 || index[c] == n || (c == 2 && 2 * k == n);
          if (!fixed) p[c] += (u - 0.5) * jitter / n;
        }
        s.points.push_back(p);
      }
  constexpr int kFaces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const std::vector<std::uint32_t> c{id(i, j, k),         id(i + 1, j, k),     id(i + 1, j + 1, k),
                                           id(i, j + 1, k),     id(i, j, k + 1),     id(i + 1, j, k + 1),
                                           id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
        if (2 * k < n) {
          add_cell(s, CellType::Hex, c, 1);
          continue;
        }
        Point3 centre{0, 0, 0};
        for (std::uint32_t v : c) centre = centre + s.points[v];
        const std::uint32_t m = std::uint32_t(s.points.size());
        s.points.push_back(centre / 8.0);
        for (int f = 0; f < 6; ++f) {
          const std::uint32_t a = c[kFaces[f][0]], b = c[kFaces[f][1]], cc = c[kFaces[f][2]], d = c[kFaces[f][3]];
          if (f == 0 && 2 * k == n) {
            add_cell(s, CellType::Pyramid, {a, b, cc, d, m}, 2);
            continue;
          }
          if (std::min(a, cc) < std::min(b, d)) {
            add_cell(s, CellType::Tet, {a, b, cc, m}, 2);
            add_cell(s, CellType::Tet, {a, cc, d, m}, 2);
          } else {
            add_cell(s, CellType::Tet, {a, b, d, m}, 2);
            add_cell(s, CellType::Tet, {b, cc, d, m}, 2);
          }
        }
      }
  tag_box_boundary(s, 0, 1);
  return s;
}

}  // namespace polydual
