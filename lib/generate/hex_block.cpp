// A structured block of hex cells as a PolyMesh: the reference mesh of the
// quality, optimiser and star-test tests and benchmarks.
#include "generate/hex_block.h"

#include <algorithm>
#include <array>

namespace polydual {

// A block of n^3 axis-aligned hex cells of size h as a PolyMesh
// Interior points are free (dim 3). Boundary points are fixed (dim 0) unless
// classify_boundary: then box-face points are {2, face tag 1..6}, box-edge points
// {1, edge tag 11..}, box corners {0, corner tag}.
PolyMesh hex_block(int n, double h, bool classify_boundary) {
  PolyMesh m;
  const int N = n + 1;
  auto pid = [&](int i, int j, int k) { return PointId((i * N + j) * N + k); };
  auto cid = [&](int i, int j, int k) { return CellId((i * n + j) * n + k); };
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j)
      for (int k = 0; k < N; ++k) {
        const int idx[3] = {i, j, k};
        int on = 0, face_tag = 0, edge_tag = 10;
        for (int d = 0; d < 3; ++d)
          if (idx[d] == 0 || idx[d] == n) {
            ++on;
            face_tag = 1 + 2 * d + (idx[d] == n);
            edge_tag += (1 + 2 * d + (idx[d] == n)) * (d == 0 ? 1 : (d == 1 ? 7 : 49));
          }
        ModelRef cls{3, 1};
        if (on > 0) cls = classify_boundary ? (on == 1 ? ModelRef{2, face_tag}
                                               : on == 2 ? ModelRef{1, edge_tag} : ModelRef{0, edge_tag})
                                            : ModelRef{0, 0};
        m.add_point({i * h, j * h, k * h}, cls);
      }
  std::vector<std::vector<HalfFace>> cells(static_cast<std::size_t>(n) * n * n);
  auto add = [&](std::array<PointId, 4> loop, bool has_lo, CellId lo, bool has_hi, CellId hi,
                 std::int32_t tag) {
    if (has_lo) {
      const FaceId f = m.add_face(loop, lo, has_hi ? hi : CellId::invalid(),
                                  has_hi ? FaceKind::Interior : FaceKind::External, has_hi ? 0 : tag);
      cells[lo.idx].push_back(HalfFace(f, 0));
      if (has_hi) cells[hi.idx].push_back(HalfFace(f, 1));
    } else {
      std::reverse(loop.begin(), loop.end());
      const FaceId f = m.add_face(loop, hi, CellId::invalid(), FaceKind::External, tag);
      cells[hi.idx].push_back(HalfFace(f, 0));
    }
  };
  for (int a = 0; a <= n; ++a)
    for (int b = 0; b < n; ++b)
      for (int c = 0; c < n; ++c) {
        // Loops with right-hand normal +x, +y, +z; the cell below the plane owns them.
        add({pid(a, b, c), pid(a, b + 1, c), pid(a, b + 1, c + 1), pid(a, b, c + 1)}, a > 0,
            a > 0 ? cid(a - 1, b, c) : CellId(), a < n, a < n ? cid(a, b, c) : CellId(), a == 0 ? 1 : 2);
        add({pid(b, a, c), pid(b, a, c + 1), pid(b + 1, a, c + 1), pid(b + 1, a, c)}, a > 0,
            a > 0 ? cid(b, a - 1, c) : CellId(), a < n, a < n ? cid(b, a, c) : CellId(), a == 0 ? 3 : 4);
        add({pid(b, c, a), pid(b + 1, c, a), pid(b + 1, c + 1, a), pid(b, c + 1, a)}, a > 0,
            a > 0 ? cid(b, c, a - 1) : CellId(), a < n, a < n ? cid(b, c, a) : CellId(), a == 0 ? 5 : 6);
      }
  for (const auto& hf : cells) m.add_cell(hf, 1, VertexId::invalid());
  return m;
}

}  // namespace polydual
