#include "quality/check_result.h"

#include <chrono>
#include <numeric>

#include "predicates/predicates.h"

namespace polydual {

namespace {
// invalid_cells and decomposition_tets from r.verdicts.
void count_verdicts(CheckResult& r) {
  r.invalid_cells = 0;
  r.decomposition_tets = 0;
  for (const CellVerdict& v : r.verdicts) {
    r.invalid_cells += !v.valid;
    r.decomposition_tets += static_cast<std::uint64_t>(v.total_tets);
  }
}

// check_mesh against `primal` (null: no model or volume check).
CheckResult check_against(const PolyMesh& mesh, const PrimalReference* primal, bool with_validation) {
  const auto t0 = std::chrono::steady_clock::now();
  CheckResult r;
  if (with_validation) r.validation = primal ? validate(mesh, *primal) : validate(mesh);
  // The exact fallbacks are counted by shared counters (predicates.h): read
  // the difference so concurrent checks of other meshes do not reset them.
  const std::uint64_t exact0 = predicate_counters().star_exact.load();
  std::vector<std::uint32_t> all(mesh.num_cells());
  std::iota(all.begin(), all.end(), 0u);
  r.verdicts.resize(mesh.num_cells());
  r.cell_exact.assign(mesh.num_cells(), 0);
  star_shaped_verdicts_of(mesh, all, r.verdicts, r.cell_exact);
  r.exact_fallbacks = predicate_counters().star_exact.load() - exact0;
  count_verdicts(r);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace

CheckResult check_with_known_verdicts(const PolyMesh& mesh, const ClassifiedTetMesh* primal, CheckResult known) {
  const auto t0 = std::chrono::steady_clock::now();
  if (known.verdicts.size() != mesh.num_cells() || known.cell_exact.size() != mesh.num_cells())
    return check_mesh(mesh, primal, true);
  CheckResult r = std::move(known);
  r.validation = validate(mesh, primal);
  count_verdicts(r);
  r.exact_fallbacks = std::accumulate(r.cell_exact.begin(), r.cell_exact.end(), std::uint64_t{0});
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

CheckResult check_mesh(const PolyMesh& mesh, const ClassifiedTetMesh* primal, bool with_validation) {
  if (!with_validation || !primal) return check_against(mesh, nullptr, with_validation);
  const auto t0 = std::chrono::steady_clock::now();
  const PrimalReference ref = primal_reference(*primal);
  CheckResult r = check_against(mesh, &ref, true);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

CheckResult check_mesh(const PolyMesh& mesh, const PrimalReference& primal, bool with_validation) {
  return check_against(mesh, &primal, with_validation);
}

Json CheckResult::to_json() const {
  Json j = Json::object();
  j.set("invalid_cells", invalid_cells);
  j.set("decomposition_tets", decomposition_tets);
  j.set("exact_fallbacks", exact_fallbacks);
  j.set("validation", validation.to_json());
  return j;
}

}  // namespace polydual
