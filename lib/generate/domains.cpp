// Gmsh meshing of the demo domains. Gmsh is one global state per process, so
// every call holds a mutex for the whole initialize..finalize session, and the
// session object finalizes even when Gmsh throws.
#include "generate/domains.h"

#include <gmsh.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/error.h"
#include "predicates/predicates.h"

namespace polydual {

namespace {

constexpr const char* kDomainNames[] = {"cube", "twomat", "fichera", "fracture", "network", "fins"};
constexpr int kDomainCount = static_cast<int>(std::size(kDomainNames));

// Gmsh 4.8 API errors arrive as std::string or std::exception depending on the
// call path; normalise them so callers see one exception type.
[[noreturn]] void rethrow_gmsh_error(const char* what_doing) {
  try {
    throw;
  } catch (const UsageError&) {
    throw;
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("gmsh failed while ") + what_doing + ": " + e.what());
  } catch (const std::string& s) {
    throw std::runtime_error(std::string("gmsh failed while ") + what_doing + ": " + s);
  } catch (...) {
    throw std::runtime_error(std::string("gmsh failed while ") + what_doing);
  }
}

std::mutex& gmsh_mutex() {
  static std::mutex m;
  return m;
}

// One initialize..finalize pair with the options that make meshing
// deterministic and silent. Holds the global Gmsh lock for its lifetime.
class GmshSession {
 public:
  GmshSession() : lock_(gmsh_mutex()) {
    // No config files: a user's ~/.gmshrc must not change our meshes.
    gmsh::initialize(0, nullptr, false);
    try {
      gmsh::option::setNumber("General.Terminal", 0);
      gmsh::option::setNumber("General.Verbosity", 0);
      // Multi-threaded meshing is not reproducible; one thread is.
      gmsh::option::setNumber("General.NumThreads", 1);
      gmsh::option::setNumber("Mesh.MaxNumThreads1D", 1);
      gmsh::option::setNumber("Mesh.MaxNumThreads2D", 1);
      gmsh::option::setNumber("Mesh.MaxNumThreads3D", 1);
      gmsh::option::setNumber("Mesh.RandomSeed", 1);
      gmsh::option::setNumber("Mesh.Algorithm", 6);    // Frontal-Delaunay surfaces
      gmsh::option::setNumber("Mesh.Algorithm3D", 1);  // Delaunay volumes
      gmsh::option::setNumber("Mesh.Optimize", 1);
      // The size comes only from the global h (set per pass), not from CAD points
      // or curvature (our domains are flat).
      gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
      gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
      gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 1);
      gmsh::model::add("polydual");
    } catch (...) {
      gmsh::finalize();
      rethrow_gmsh_error("setting options");
    }
  }
  ~GmshSession() { gmsh::finalize(); }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

 private:
  std::lock_guard<std::mutex> lock_;
};

double domain_volume(Domain d) {
  switch (d) {
    case Domain::Cube: return 1.0;
    case Domain::TwoMat: return 2.0;
    case Domain::Fichera: return 1.0 - 0.125;
    case Domain::Fracture: return 1.0;
    case Domain::Network: return 1.0;
    case Domain::Fins: return 1.0;
  }
  return 1.0;
}

// Volume entity tag whose centre of mass is c (within 1e-9), or -1.
int volume_at(double cx, double cy, double cz) {
  gmsh::vectorpair vols;
  gmsh::model::getEntities(vols, 3);
  for (auto [dim, tag] : vols) {
    double x, y, z;
    gmsh::model::occ::getCenterOfMass(dim, tag, x, y, z);
    if (std::abs(x - cx) < 1e-9 && std::abs(y - cy) < 1e-9 && std::abs(z - cz) < 1e-9) return tag;
  }
  return -1;
}

// An axis-aligned rectangle in the plane x[axis] = at, spanning [lo0,hi0] x
// [lo1,hi1] in the other two coordinates (in increasing axis order).
struct Sheet {
  int axis;
  double at, lo0, hi0, lo1, hi1;
};

// Fracture network: three rectangles crossing pairwise along lines that meet at
// (0.5,0.5,0.5); the first meets the wall x=0, the others end inside.
std::vector<Sheet> network_sheets() {
  return {{2, 0.5, 0.0, 0.7, 0.2, 0.8}, {1, 0.5, 0.3, 0.9, 0.2, 0.8}, {0, 0.5, 0.25, 0.75, 0.3, 0.7}};
}

// Fins: three disjoint rectangles, each attached to one wall along a segment.
std::vector<Sheet> fins_sheets() {
  return {{1, 0.5, 0.0, 0.4, 0.2, 0.8}, {2, 0.5, 0.6, 1.0, 0.2, 0.8}, {0, 0.5, 0.65, 1.0, 0.25, 0.75}};
}

// Unit box fragmented by the sheets: the mesh becomes conformal to every sheet
// and to their intersections, and the box stays one region.
void embed_sheets(const std::vector<Sheet>& sheets) {
  namespace occ = gmsh::model::occ;
  const int box = occ::addBox(0, 0, 0, 1, 1, 1, 1);
  gmsh::vectorpair tools;
  for (const Sheet& s : sheets) {
    // addRectangle lies in z = const; rotate it into the sheet's plane.
    int r = 0;
    if (s.axis == 2) {
      r = occ::addRectangle(s.lo0, s.lo1, s.at, s.hi0 - s.lo0, s.hi1 - s.lo1);
    } else if (s.axis == 1) {
      // (x, z) rectangle: draw in the xy plane at y=0 and rotate about x by +90
      // degrees, which maps (x, y, 0) to (x, 0, y).
      r = occ::addRectangle(s.lo0, s.lo1, 0, s.hi0 - s.lo0, s.hi1 - s.lo1);
      occ::rotate({{2, r}}, 0, 0, 0, 1, 0, 0, M_PI / 2);
      occ::translate({{2, r}}, 0, s.at, 0);
    } else {
      // (y, z) rectangle: draw as (y, z) in the xy plane, rotate about x (to
      // (a, 0, b)) and then about z by +90 degrees (to (0, a, b)).
      r = occ::addRectangle(s.lo0, s.lo1, 0, s.hi0 - s.lo0, s.hi1 - s.lo1);
      occ::rotate({{2, r}}, 0, 0, 0, 1, 0, 0, M_PI / 2);
      occ::rotate({{2, r}}, 0, 0, 0, 0, 0, 1, M_PI / 2);
      occ::translate({{2, r}}, s.at, 0, 0);
    }
    tools.push_back({2, r});
  }
  gmsh::vectorpair out;
  std::vector<gmsh::vectorpair> out_map;
  occ::fragment({{3, box}}, tools, out, out_map);
  occ::synchronize();
}

// Model surfaces each construction must produce (the network's crossing lines
// cut the sheet x=0.5 into four faces; the other two stay one face each, with
// the crossing segments as curves embedded in them: 1 + 1 + 4 sheet faces).
std::size_t expected_surfaces(Domain d) {
  switch (d) {
    case Domain::Cube: return 6;
    case Domain::TwoMat: return 11;
    case Domain::Fichera: return 9;
    case Domain::Fracture: return 7;
    case Domain::Network: return 6 + 6;
    case Domain::Fins: return 6 + 3;
  }
  return 0;
}

// Builds the CAD of domain d in the OCC kernel and synchronises the model.
// Checks the topology each construction promises, since a silent change in
// OCC's boolean results would give a different domain than the paper's.
void build_geometry(Domain d) {
  namespace occ = gmsh::model::occ;
  gmsh::vectorpair out;
  std::vector<gmsh::vectorpair> out_map;
  switch (d) {
    case Domain::Cube:
      occ::addBox(0, 0, 0, 1, 1, 1, 1);
      occ::synchronize();
      break;
    case Domain::TwoMat: {
      // Fragment (general fuse) makes the shared face x=1 one conformal surface
      // bounding both volumes: the material interface.
      int a = occ::addBox(0, 0, 0, 1, 1, 1, 1);
      int b = occ::addBox(1, 0, 0, 1, 1, 1, 2);
      occ::fragment({{3, a}}, {{3, b}}, out, out_map);
      occ::synchronize();
      if (volume_at(0.5, 0.5, 0.5) != 1 || volume_at(1.5, 0.5, 0.5) != 2)
        throw std::logic_error("twomat: OCC fragment did not keep region tags 1 (x<1), 2 (x>1)");
      break;
    }
    case Domain::Fichera: {
      int a = occ::addBox(0, 0, 0, 1, 1, 1, 1);
      int b = occ::addBox(0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 2);
      occ::cut({{3, a}}, {{3, b}}, out, out_map);
      occ::synchronize();
      break;
    }
    case Domain::Fracture: {
      int a = occ::addBox(0, 0, 0, 1, 1, 1, 1);
      int s = occ::addRectangle(0, 0.2, 0.5, 0.6, 0.6, 100);
      // Fragmenting a volume with a surface inside it embeds the surface (Gmsh
      // docs): the mesh becomes conformal to it, and it bounds no second region.
      occ::fragment({{3, a}}, {{2, s}}, out, out_map);
      occ::synchronize();
      break;
    }
    case Domain::Network:
    case Domain::Fins:
      embed_sheets(d == Domain::Network ? network_sheets() : fins_sheets());
      break;
  }
  gmsh::vectorpair vols, faces;
  gmsh::model::getEntities(vols, 3);
  gmsh::model::getEntities(faces, 2);
  const std::size_t want_vols = d == Domain::TwoMat ? 2 : 1;
  const std::size_t want_faces = expected_surfaces(d);
  if (vols.size() != want_vols || faces.size() != want_faces)
    throw std::logic_error(domain_name(d) + ": unexpected CAD topology (" +
                           std::to_string(vols.size()) + " volumes, " +
                           std::to_string(faces.size()) + " surfaces)");
  if (d == Domain::Fracture || d == Domain::Network || d == Domain::Fins) {
    // The sheets must be inside the volume (embedded), not on its boundary.
    gmsh::vectorpair bnd;
    gmsh::model::getBoundary(vols, bnd, false, false, false);
    if (bnd.size() != 6)
      throw std::logic_error(domain_name(d) + ": the sheets were not embedded in the volume");
  }
}

std::size_t count_tets() {
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> tags, nodes;
  gmsh::model::mesh::getElements(types, tags, nodes, 3, -1);
  std::size_t n = 0;
  for (std::size_t i = 0; i < types.size(); ++i)
    if (types[i] == 4) n += tags[i].size();
  return n;
}

void mesh_with_size(double h) {
  gmsh::model::mesh::clear();
  gmsh::option::setNumber("Mesh.MeshSizeMin", h);
  gmsh::option::setNumber("Mesh.MeshSizeMax", h);
  gmsh::model::mesh::generate(3);
}

// Meshes the current model with about `target` tets. Delaunay meshes with a
// uniform size h have about c·V/h^3 tets; c depends on the algorithm and, for
// coarse meshes, on the boundary, and the count jumps whenever the number of
// segments on a model edge changes. So: measure c on a trial of at most
// kCalibrationTets, then search h (secant on log n against log h, bisection once
// the target is bracketed) and keep the closest pass. Every step depends only
// on (domain, target), so the result is deterministic.
void mesh_to_target(Domain d, std::size_t target) {
  constexpr std::size_t kCalibrationTets = 20000;
  constexpr double kInitialDensity = 7.0;  // tets per h^3, Gmsh Delaunay, measured
  const double V = domain_volume(d);
  const double goal_n = static_cast<double>(target);
  auto h_for = [V](double c, double n) { return std::cbrt(c * V / n); };

  // Trial for big targets: its density extrapolates well (boundary share shrinks).
  double c = kInitialDensity;
  if (target > kCalibrationTets) {
    const double h = h_for(c, kCalibrationTets);
    mesh_with_size(h);
    c = static_cast<double>(count_tets()) * h * h * h / V;
  }
  // Big meshes are costly to redo, so they get fewer passes and a looser
  // tolerance (the trial's density extrapolates to within ~10% there).
  const bool big = target > 200000;
  const int max_passes = big ? 2 : 8;
  const double tolerance = std::log(big ? 1.15 : 1.05);
  double best_h = 0, best_err = std::numeric_limits<double>::infinity();
  double lo_h = 0, hi_h = 0;  // h giving too many tets (small h) / too few (large h)
  double h = h_for(c, goal_n);
  double last_h = 0;
  for (int pass = 0; pass < max_passes; ++pass) {
    mesh_with_size(h);
    last_h = h;
    const double n = static_cast<double>(count_tets());
    if (n == 0) throw std::runtime_error(domain_name(d) + ": gmsh produced no tetrahedra");
    const double err = std::abs(std::log(n / goal_n));
    if (err < best_err) best_err = err, best_h = h;
    if (best_err <= tolerance) break;
    if (n > goal_n) lo_h = h; else hi_h = h;
    c = n * h * h * h / V;
    double next = h_for(c, goal_n);
    // Once bracketed, stay strictly inside the bracket (the count is a step
    // function of h at coarse sizes, so the secant alone can cycle).
    if (lo_h > 0 && hi_h > 0 && (next <= lo_h || next >= hi_h || pass >= 3))
      next = std::sqrt(lo_h * hi_h);
    h = next;
  }
  if (last_h != best_h) mesh_with_size(best_h);
}

// Node tag -> compact index, in increasing node-tag order over the nodes that
// tets use (every node of a Gmsh volume mesh is in some tet; compacting guards
// against strays so classify() never sees unused vertices).
TetSoup extract_soup(Domain d) {
  TetSoup soup;
  soup.source = "<generated " + domain_name(d) + ">";
  soup.full_classification = true;

  std::vector<std::size_t> node_tags;
  std::vector<double> coord, param;
  gmsh::model::mesh::getNodes(node_tags, coord, param, -1, -1, false, false);
  std::size_t max_tag = 0;
  for (auto t : node_tags) max_tag = std::max(max_tag, t);
  std::vector<std::size_t> coord_of(max_tag + 1, std::numeric_limits<std::size_t>::max());
  for (std::size_t i = 0; i < node_tags.size(); ++i) coord_of[node_tags[i]] = i;

  auto entities_sorted = [](int dim) {
    gmsh::vectorpair e;
    gmsh::model::getEntities(e, dim);
    std::sort(e.begin(), e.end());
    return e;
  };
  auto elements_of = [](int dim, int tag, int type) {
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> tags, nodes;
    gmsh::model::mesh::getElements(types, tags, nodes, dim, tag);
    for (std::size_t i = 0; i < types.size(); ++i)
      if (types[i] == type) return std::move(nodes[i]);
    return std::vector<std::size_t>{};
  };

  // Pass 1: tets, and which nodes they use.
  std::vector<std::pair<int, std::vector<std::size_t>>> tet_blocks;
  std::vector<std::uint32_t> index_of(max_tag + 1, std::numeric_limits<std::uint32_t>::max());
  for (auto [dim, tag] : entities_sorted(3)) {
    auto nodes = elements_of(3, tag, 4);
    for (auto n : nodes) index_of[n] = 0;
    tet_blocks.emplace_back(tag, std::move(nodes));
  }
  std::uint32_t next = 0;
  for (std::size_t t = 0; t <= max_tag; ++t) {
    if (index_of[t] == std::numeric_limits<std::uint32_t>::max()) continue;
    if (coord_of[t] == std::numeric_limits<std::size_t>::max())
      throw std::runtime_error(domain_name(d) + ": gmsh element uses an unknown node");
    index_of[t] = next++;
    const std::size_t c = coord_of[t];
    soup.points.push_back({coord[3 * c], coord[3 * c + 1], coord[3 * c + 2]});
  }
  auto idx = [&](std::size_t node_tag) {
    if (node_tag > max_tag || index_of[node_tag] == std::numeric_limits<std::uint32_t>::max())
      throw std::runtime_error(domain_name(d) + ": gmsh boundary element off the volume mesh");
    return index_of[node_tag];
  };

  for (auto& [tag, nodes] : tet_blocks) {
    for (std::size_t i = 0; i + 3 < nodes.size(); i += 4) {
      std::array<std::uint32_t, 4> t{idx(nodes[i]), idx(nodes[i + 1]), idx(nodes[i + 2]),
                                     idx(nodes[i + 3])};
      // Gmsh promises positive tets, but the dual relies on it, so decide exactly.
      const Sign s = orient3d(soup.points[t[0]], soup.points[t[1]], soup.points[t[2]],
                              soup.points[t[3]]);
      if (s == Sign::Zero)
        throw std::runtime_error(domain_name(d) + ": gmsh produced a flat tetrahedron");
      if (s == Sign::Negative) std::swap(t[2], t[3]);
      soup.tets.push_back(t);
      soup.tet_region.push_back(tag);
    }
  }
  for (auto [dim, tag] : entities_sorted(2)) {
    auto nodes = elements_of(2, tag, 2);
    for (std::size_t i = 0; i + 2 < nodes.size(); i += 3)
      soup.triangles.push_back({{idx(nodes[i]), idx(nodes[i + 1]), idx(nodes[i + 2])}, tag});
  }
  for (auto [dim, tag] : entities_sorted(1)) {
    auto nodes = elements_of(1, tag, 1);
    for (std::size_t i = 0; i + 1 < nodes.size(); i += 2)
      soup.edges.push_back({{idx(nodes[i]), idx(nodes[i + 1])}, tag});
  }
  for (auto [dim, tag] : entities_sorted(0)) {
    for (auto n : elements_of(0, tag, 15)) soup.corners.push_back({idx(n), tag});
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
  for (int i = 0; i < kDomainCount; ++i)
    if (name == kDomainNames[i]) return static_cast<Domain>(i);
  throw UsageError("unknown domain '" + name +
                   "' (valid: cube|twomat|fichera|fracture|network|fins)");
}

std::string domain_name(Domain d) { return kDomainNames[static_cast<int>(d)]; }

TetSoup generate_domain(Domain d, std::size_t target_tets) {
  check_target(target_tets);
  GmshSession session;
  try {
    build_geometry(d);
    mesh_to_target(d, target_tets);
    return extract_soup(d);
  } catch (const std::logic_error&) {
    throw;
  } catch (...) {
    rethrow_gmsh_error(("meshing " + domain_name(d)).c_str());
  }
}

void write_domain_msh(Domain d, std::size_t target_tets, const std::string& path) {
  check_target(target_tets);
  // gmsh::write picks the format from the extension, so the temporary keeps ".msh".
  const std::string tmp = path + ".tmp." + std::to_string(::getpid()) + ".msh";
  GmshSession session;
  try {
    build_geometry(d);
    mesh_to_target(d, target_tets);
    // SaveAll: without physical groups Gmsh writes everything anyway, but the
    // option makes that explicit and survives a later physical group.
    gmsh::option::setNumber("Mesh.SaveAll", 1);
    gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
    gmsh::option::setNumber("Mesh.Binary", 0);
    gmsh::write(tmp);
    std::filesystem::rename(tmp, path);
  } catch (...) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    try {
      throw;
    } catch (const std::logic_error&) {
      throw;
    } catch (const std::filesystem::filesystem_error&) {
      throw;
    } catch (...) {
      rethrow_gmsh_error(("writing " + path).c_str());
    }
  }
}

}  // namespace polydual
