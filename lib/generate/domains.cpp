// The demo domains as TetSoups: names, the target check, and the conversion of
// Gmsh's raw mesh (generate/gmsh_module.h) into a soup whose tets are
// positively oriented by the exact predicate. Gmsh itself is reached through
// gmsh_module::gmsh_api() only.
#include "generate/domains.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/interrupt.h"
#include "generate/gmsh_module.h"
#include "predicates/predicates.h"

namespace polydual {

namespace {

constexpr const char* kDomainNames[] = {"cube", "twomat", "fichera", "fracture", "network", "fins", "layers", "dfn"};
static_assert(std::size(kDomainNames) == gmsh_module::kNumDomains);

constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
constexpr std::size_t kNoCoord = std::numeric_limits<std::size_t>::max();

// Node tag -> position in raw.coords.
std::vector<std::size_t> coord_positions(const gmsh_module::RawMesh& raw, std::size_t max_tag) {
  std::vector<std::size_t> coord_of(max_tag + 1, kNoCoord);
  for (std::size_t i = 0; i < raw.node_tags.size(); ++i) coord_of[raw.node_tags[i]] = i;
  return coord_of;
}

// Node tag -> compact index, in increasing node-tag order over the nodes that
// tets use (every node of a Gmsh volume mesh is in some tet; compacting guards
// against strays so classify() never sees unused vertices); fills soup.points.
std::vector<std::uint32_t> number_tet_nodes(Domain d, const gmsh_module::RawMesh& raw, TetSoup& soup) {
  std::size_t max_tag = 0;
  for (auto t : raw.node_tags) max_tag = std::max(max_tag, t);
  for (const auto& b : raw.blocks)
    for (auto n : b.nodes) max_tag = std::max(max_tag, n);
  const std::vector<std::size_t> coord_of = coord_positions(raw, max_tag);
  std::vector<std::uint32_t> index_of(max_tag + 1, kUnused);
  for (const auto& b : raw.blocks)
    if (b.dim == 3)
      for (auto n : b.nodes) index_of[n] = 0;
  std::uint32_t next = 0;
  for (std::size_t t = 0; t <= max_tag; ++t) {
    if (index_of[t] == kUnused) continue;
    if (coord_of[t] == kNoCoord) throw std::runtime_error(domain_name(d) + ": gmsh element uses an unknown node");
    index_of[t] = next++;
    const std::size_t c = coord_of[t];
    soup.points.push_back({raw.coords[3 * c], raw.coords[3 * c + 1], raw.coords[3 * c + 2]});
  }
  return index_of;
}

// The soup of a raw Gmsh mesh: tets per volume, then triangles, segments and
// points per model entity, each group in tag order.
TetSoup soup_from_raw(Domain d, const gmsh_module::RawMesh& raw) {
  TetSoup soup;
  soup.source = "<generated " + domain_name(d) + ">";
  soup.full_classification = true;
  const std::vector<std::uint32_t> index_of = number_tet_nodes(d, raw, soup);
  auto idx = [&](std::size_t node_tag) {
    if (node_tag >= index_of.size() || index_of[node_tag] == kUnused)
      throw std::runtime_error(domain_name(d) + ": gmsh boundary element off the volume mesh");
    return index_of[node_tag];
  };
  for (const auto& b : raw.blocks) {
    const auto& n = b.nodes;
    if (b.dim == 3) {
      for (std::size_t i = 0; i + 3 < n.size(); i += 4) {
        std::array<std::uint32_t, 4> t{idx(n[i]), idx(n[i + 1]), idx(n[i + 2]), idx(n[i + 3])};
        // Gmsh promises positive tets, but the dual relies on it, so decide exactly.
        const Sign s = orient3d(soup.points[t[0]], soup.points[t[1]], soup.points[t[2]], soup.points[t[3]]);
        if (s == Sign::Zero) throw std::runtime_error(domain_name(d) + ": gmsh produced a flat tetrahedron");
        if (s == Sign::Negative) std::swap(t[2], t[3]);
        soup.tets.push_back(t);
        soup.tet_region.push_back(b.tag);
      }
    } else if (b.dim == 2) {
      for (std::size_t i = 0; i + 2 < n.size(); i += 3)
        soup.triangles.push_back({{idx(n[i]), idx(n[i + 1]), idx(n[i + 2])}, b.tag});
    } else if (b.dim == 1) {
      for (std::size_t i = 0; i + 1 < n.size(); i += 2) soup.edges.push_back({{idx(n[i]), idx(n[i + 1])}, b.tag});
    } else {
      for (auto v : n) soup.corners.push_back({idx(v), b.tag});
    }
  }
  return soup;
}

void check_target(std::size_t target) {
  if (target < kMinTargetTets || target > kMaxTargetTets)
    throw UsageError("target number of tets must be in [" + std::to_string(kMinTargetTets) +
                     ", " + std::to_string(kMaxTargetTets) + "], got " +
                     std::to_string(target));
}

}  // namespace

Domain parse_domain(const std::string& name) {
  for (int i = 0; i < gmsh_module::kNumDomains; ++i)
    if (name == kDomainNames[i]) return static_cast<Domain>(i);
  std::string valid;
  for (const char* n : kDomainNames) valid += (valid.empty() ? "" : "|") + std::string(n);
  throw UsageError("unknown domain '" + name + "' (valid: " + valid + ")");
}

DomainKind domain_kind(Domain d) {
  return d == Domain::Layers ? DomainKind::Mixed : d == Domain::Dfn ? DomainKind::Surface : DomainKind::Tets;
}

std::string domain_name(Domain d) { return kDomainNames[static_cast<int>(d)]; }

TetSoup generate_domain(Domain d, std::size_t target_tets) {
  check_target(target_tets);
  if (domain_kind(d) != DomainKind::Tets)
    throw UsageError("domain '" + domain_name(d) + "' is a " +
                     (domain_kind(d) == DomainKind::Mixed ? "mixed" : "surface") +
                     " mesh: it is generated as a Gmsh .msh file only");
  const gmsh_module::GmshApi& gmsh = gmsh_module::gmsh_api();
  gmsh_module::RawMesh raw;
  std::string error;
  if (!gmsh.mesh(static_cast<int>(d), target_tets, raw, error)) throw std::runtime_error(error);
  return soup_from_raw(d, raw);
}

void write_domain_msh(Domain d, std::size_t target_tets, const std::string& path) {
  check_target(target_tets);
  throw_if_interrupted();
  const gmsh_module::GmshApi& gmsh = gmsh_module::gmsh_api();
  // Gmsh picks the format from the extension, so the temporary keeps ".msh".
  const std::string tmp = path + ".tmp." + std::to_string(::getpid()) + ".msh";
  // Gmsh does not poll the interrupt flag: a signal while it meshes ends the
  // run through the watchdog (core/interrupt.h), which removes this file.
  ScopedTemporary registered(tmp, ScopedTemporary::Kind::File);
  std::string error;
  if (!gmsh.write_msh(static_cast<int>(d), target_tets, tmp.c_str(), error)) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    // The message names the file the user asked for, not the temporary.
    for (std::size_t at; (at = error.find(tmp)) != std::string::npos;) error.replace(at, tmp.size(), path);
    throw std::runtime_error(error);
  }
  try {
    const auto commit = hold_off_watchdog();
    throw_if_interrupted();  // nothing is written after a signal
    std::filesystem::rename(tmp, path);
  } catch (...) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw;
  }
}

}  // namespace polydual
