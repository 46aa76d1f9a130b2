#include "split/recheck.h"

#include <bit>
#include <chrono>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "quality/star_verdict.h"

namespace polydual {

namespace {

bool same_point(const Point3& a, const Point3& b) {
  return std::bit_cast<std::uint64_t>(a.x) == std::bit_cast<std::uint64_t>(b.x) &&
         std::bit_cast<std::uint64_t>(a.y) == std::bit_cast<std::uint64_t>(b.y) &&
         std::bit_cast<std::uint64_t>(a.z) == std::bit_cast<std::uint64_t>(b.z);
}

// Per cell of fresh, its partner in old (invalid: none): runs of equal
// cell_primal are one vertex's cells, in the same vertex order in both meshes.
std::vector<CellId> partners(const PolyMesh& fresh, const PolyMesh& old) {
  std::vector<CellId> out(fresh.num_cells(), CellId::invalid());
  const std::size_t nf = fresh.num_cells(), no = old.num_cells();
  std::size_t i = 0, j = 0;
  while (i < nf && j < no) {
    const VertexId v = fresh.cell_primal[i];
    if (old.cell_primal[j] != v) break;  // not the same vertex order: no more partners
    std::size_t ei = i, ej = j;
    while (ei < nf && fresh.cell_primal[ei] == v) ++ei;
    while (ej < no && old.cell_primal[ej] == v) ++ej;
    if (ei - i == ej - j)
      for (std::size_t k = 0; k < ei - i; ++k) out[i + k] = CellId(j + k);
    i = ei;
    j = ej;
  }
  return out;
}

}  // namespace

bool same_cell(const PolyMesh& fresh, CellId c, const PolyMesh& old, CellId d, std::span<const PointId> from_old) {
  const auto hc = fresh.cell(c), hd = old.cell(d);
  if (hc.size() != hd.size()) return false;
  for (std::size_t h = 0; h < hc.size(); ++h) {
    const auto fc = fresh.face(hc[h].face()), fd = old.face(hd[h].face());
    const std::size_t k = fc.size();
    if (fd.size() != k) return false;
    for (std::size_t i = 0; i < k; ++i) {
      const PointId p = hc[h].side() == 0 ? fc[i] : fc[k - 1 - i];
      const PointId q = hd[h].side() == 0 ? fd[i] : fd[k - 1 - i];
      if (p.idx >= from_old.size() || from_old[p.idx] != q) return false;
      if (!same_point(fresh.points[p.idx], old.points[q.idx])) return false;
    }
  }
  return true;
}

CheckResult recheck_mesh(const PolyMesh& fresh, const PolyMesh& old, const CheckResult& old_check,
                         std::span<const PointId> from_old, RecheckStats* stats) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n = fresh.num_cells();
  const bool known = old_check.verdicts.size() == old.num_cells() && old_check.cell_exact.size() == old.num_cells();
  CheckResult r;
  r.verdicts.assign(n, CellVerdict{});
  r.cell_exact.assign(n, 0);
  // Phase 1: carry over the verdicts of the cells that did not change.
  std::vector<char> redo(n, 1);
  if (known) {
    const std::vector<CellId> partner = partners(fresh, old);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 512), [&](const auto& range) {
      for (std::size_t c = range.begin(); c != range.end(); ++c) {
        const CellId d = partner[c];
        if (!d.valid() || !same_cell(fresh, CellId(c), old, d, from_old)) continue;
        r.verdicts[c] = old_check.verdicts[d.idx];
        r.cell_exact[c] = old_check.cell_exact[d.idx];
        redo[c] = 0;
      }
    });
  }
  // Phase 2: the star test of the others.
  std::vector<std::uint32_t> cells;
  for (std::size_t c = 0; c < n; ++c)
    if (redo[c]) cells.push_back(std::uint32_t(c));
  star_shaped_verdicts_of(fresh, cells, r.verdicts, r.cell_exact);
  for (std::size_t c = 0; c < n; ++c) {
    r.invalid_cells += !r.verdicts[c].valid;
    r.decomposition_tets += std::uint64_t(r.verdicts[c].total_tets);
    r.exact_fallbacks += r.cell_exact[c];
  }
  if (stats) *stats = RecheckStats{n - cells.size(), cells.size()};
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace polydual
