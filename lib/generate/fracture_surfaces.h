// Surface meshes of planar fracture networks made without a mesher (design
// §15): axis-aligned rectangles triangulated on one lattice, so that where
// two fractures cross their triangles share the crossing line's edges
// exactly (conformal), for the surface dual's demo, tests and experiments.
//
// Lattice: unit u = 1/(2n). A rectangle is meshed in rows of constant t every
// 2u; a row whose index t/2 is even has points at even s, an odd row at odd s
// plus its two ends, and consecutive rows are zipped into triangles of base
// 2u and height 2u (all acute but the right triangles at odd rows' ends), so
// the circumcentres of neighbouring triangles never coincide. Points are
// merged by lattice coordinates, so every row both fractures hold (a crossing
// line) is one chain of edges. Every coordinate s0, s1, t0, t1, offset is an
// even number of units; a crossing line must lie on a row with t/2 even in
// both fractures.
#pragma once
#include <vector>

#include "mesh/tet_soup.h"

namespace polydual {

struct LatticeRectangle {
  int axis = 2;      // the normal's axis: 0 (plane x = offset), 1 (y) or 2 (z)
  int offset = 0;    // the plane's coordinate, in units u
  int row_axis = 0;  // the axis of s (rows run along it); t is the third axis
  // The ranges of s and t, in units u, s0 < s1, t0 < t1.
  int s0 = 0, s1 = 0, t0 = 0, t1 = 0;
  int tag = 1;     // the surface tag of its triangles
};

// The triangles of the rectangles as a surface soup (no volume cell; each
// triangle tagged with its rectangle's tag, counterclockwise in (s, t)).
// UsageError for n < 1 or a rectangle off the lattice rules above.
TetSoup lattice_rectangles_soup(const std::vector<LatticeRectangle>& rects, int n, const std::string& source);

// The demo network, n a positive multiple of 4 (about 17 n^2 triangles):
// F1 = the square z = 0, x, y in [-1, 1]; F2 = y = 0, x, z in [-1, 1],
// crossing F1 along the x axis; F3 = y = 0.5, x in [0.25, 0.75], z in
// [-0.5, 0.5], crossing F1 along a segment that ends inside F1.
TetSoup fracture_network_surface(int n);

}  // namespace polydual
