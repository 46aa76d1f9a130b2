// Gmsh meshing of the demo domains: the only code of polydual that calls
// Gmsh (generate/gmsh_module.h). Gmsh is one global state per process, so
// every call holds a mutex for the whole initialize..finalize session, and the
// session object finalizes even when Gmsh throws. Nothing here throws across
// the table: every entry catches and returns the message.
#include <gmsh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

#include "generate/domains.h"  // the Domain enum only (no polydual code is linked)
#include "generate/gmsh_module.h"

namespace polydual {

namespace {

constexpr const char* kNames[] = {"cube", "twomat", "fichera", "fracture", "network", "fins", "layers", "dfn"};
std::string name_of(Domain d) { return kNames[static_cast<int>(d)]; }

// A failure whose message is already complete (the session's options).
class GmshFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Gmsh 4.8 API errors arrive as std::string or std::exception depending on the
// call path; normalise them into one message. The CAD checks below throw
// std::logic_error with a complete message, kept as it is.
std::string gmsh_error_message(const std::string& what_doing) {
  try {
    throw;
  } catch (const GmshFailure& e) {
    return e.what();
  } catch (const std::logic_error& e) {
    return e.what();
  } catch (const std::exception& e) {
    return "gmsh failed while " + what_doing + ": " + e.what();
  } catch (const std::string& s) {
    return "gmsh failed while " + what_doing + ": " + s;
  } catch (...) {
    return "gmsh failed while " + what_doing;
  }
}

[[noreturn]] void rethrow_gmsh_error(const char* what_doing) {
  throw GmshFailure(gmsh_error_message(what_doing));
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

// The measure the element count scales with: the volume of a tet domain, the
// area of the layers domain's cross-section (its extrusion has a fixed number
// of layers) and the area of the fracture network.
double domain_measure(Domain d) {
  switch (d) {
    case Domain::Cube: return 1.0;
    case Domain::TwoMat: return 2.0;
    case Domain::Fichera: return 1.0 - 0.125;
    case Domain::Fracture: return 1.0;
    case Domain::Network: return 1.0;
    case Domain::Fins: return 1.0;
    case Domain::Layers: return 6.0 * 3.0 - M_PI * 0.25;
    case Domain::Dfn: return 0.7 * 0.6 + 0.6 * 0.6 + 0.5 * 0.4;
  }
  return 1.0;
}

// The dimension the element count scales with (h^-k elements for size h).
int count_exponent(Domain d) { return d == Domain::Layers || d == Domain::Dfn ? 2 : 3; }

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

// One sheet as an OCC rectangle in its plane; returns its surface tag.
int add_sheet(const Sheet& s) {
  namespace occ = gmsh::model::occ;
  // addRectangle lies in z = const; rotate it into the sheet's plane.
  if (s.axis == 2) return occ::addRectangle(s.lo0, s.lo1, s.at, s.hi0 - s.lo0, s.hi1 - s.lo1);
  const int r = occ::addRectangle(s.lo0, s.lo1, 0, s.hi0 - s.lo0, s.hi1 - s.lo1);
  if (s.axis == 1) {
    // (x, z) rectangle: drawn in the xy plane at y=0 and rotated about x by +90
    // degrees, which maps (x, y, 0) to (x, 0, y).
    occ::rotate({{2, r}}, 0, 0, 0, 1, 0, 0, M_PI / 2);
    occ::translate({{2, r}}, 0, s.at, 0);
  } else {
    // (y, z) rectangle: drawn as (y, z) in the xy plane, rotated about x (to
    // (a, 0, b)) and then about z by +90 degrees (to (0, a, b)).
    occ::rotate({{2, r}}, 0, 0, 0, 1, 0, 0, M_PI / 2);
    occ::rotate({{2, r}}, 0, 0, 0, 0, 0, 1, M_PI / 2);
    occ::translate({{2, r}}, s.at, 0, 0);
  }
  return r;
}

// Unit box fragmented by the sheets: the mesh becomes conformal to every sheet
// and to their intersections, and the box stays one region.
void embed_sheets(const std::vector<Sheet>& sheets) {
  namespace occ = gmsh::model::occ;
  const int box = occ::addBox(0, 0, 0, 1, 1, 1, 1);
  gmsh::vectorpair tools;
  for (const Sheet& s : sheets) tools.push_back({2, add_sheet(s)});
  gmsh::vectorpair out;
  std::vector<gmsh::vectorpair> out_map;
  occ::fragment({{3, box}}, tools, out, out_map);
  occ::synchronize();
}

// The fracture network's sheets on their own (a surface mesh, as a
// discrete-fracture-network code takes it): fragmented with each other, so
// the triangles are conformal along the crossing lines.
void sheets_alone(const std::vector<Sheet>& sheets) {
  namespace occ = gmsh::model::occ;
  gmsh::vectorpair objects, tools, out;
  for (const Sheet& s : sheets) (objects.empty() ? objects : tools).push_back({2, add_sheet(s)});
  std::vector<gmsh::vectorpair> out_map;
  occ::fragment(objects, tools, out, out_map);
  occ::synchronize();
}

// The layers domain: a channel [-2,4]x[-1.5,1.5] around a cylinder of radius
// 0.5 at the origin, a 2D mesh with a quadrangle boundary layer on the
// cylinder's wall (first layer kFirstLayer thick, ratio 1.3, about six
// layers) extruded over kLayersDepth in kLayersNz recombined layers:
// hexahedra in the wall layers, prisms elsewhere (a CFD boundary layer).
constexpr double kFirstLayer = 0.01, kLayersDepth = 0.4;
constexpr int kLayersNz = 4;
constexpr int kWallSizeField = 2;  // the size field refined at the wall, per pass

void channel_with_layers() {
  namespace occ = gmsh::model::occ;
  namespace field = gmsh::model::mesh::field;
  const int rect = occ::addRectangle(-2, -1.5, 0, 6, 3);
  const int disk = occ::addDisk(0, 0, 0, 0.5, 0.5);
  gmsh::vectorpair out;
  std::vector<gmsh::vectorpair> out_map;
  occ::cut({{2, rect}}, {{2, disk}}, out, out_map);
  occ::synchronize();
  if (out.size() != 1) throw std::logic_error("layers: the channel minus the cylinder is not one surface");
  const int surface = out[0].second;
  gmsh::vectorpair curves;
  gmsh::model::getBoundary(out, curves, false, false, false);
  int wall = -1;
  for (auto [dim, tag] : curves) {
    double x, y, z;
    occ::getCenterOfMass(dim, std::abs(tag), x, y, z);
    if (std::abs(x) < 1e-9 && std::abs(y) < 1e-9) wall = std::abs(tag);
  }
  if (wall < 0) throw std::logic_error("layers: no cylinder wall among the channel's curves");
  field::add("BoundaryLayer", 1);
  field::setNumbers(1, "CurvesList", {double(wall)});
  field::setNumber(1, "Size", kFirstLayer);
  field::setNumber(1, "Ratio", 1.3);
  field::setNumber(1, "Thickness", 8 * kFirstLayer);
  field::setNumber(1, "Quads", 1);
  field::setAsBoundaryLayer(1);
  // Smaller cells near the wall: the sizes are set per pass (mesh_with_size).
  field::add("Distance", 3);
  field::setNumbers(3, "CurvesList", {double(wall)});
  field::add("Threshold", kWallSizeField);
  field::setNumber(kWallSizeField, "InField", 3);
  field::setNumber(kWallSizeField, "DistMin", 0.1);
  field::setNumber(kWallSizeField, "DistMax", 1.0);
  field::setAsBackgroundMesh(kWallSizeField);
  occ::extrude({{2, surface}}, 0, 0, kLayersDepth, out, {kLayersNz}, {}, true);
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
    case Domain::Layers: return 7;  // bottom, top, four channel walls, the cylinder's
    case Domain::Dfn: return 6;     // the network's sheet faces, without the box
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
    case Domain::Layers: channel_with_layers(); break;
    case Domain::Dfn: sheets_alone(network_sheets()); break;
  }
  gmsh::vectorpair vols, faces;
  gmsh::model::getEntities(vols, 3);
  gmsh::model::getEntities(faces, 2);
  const std::size_t want_vols = d == Domain::TwoMat ? 2 : d == Domain::Dfn ? 0 : 1;
  const std::size_t want_faces = expected_surfaces(d);
  if (vols.size() != want_vols || faces.size() != want_faces)
    throw std::logic_error(name_of(d) + ": unexpected CAD topology (" +
                           std::to_string(vols.size()) + " volumes, " +
                           std::to_string(faces.size()) + " surfaces)");
  if (d == Domain::Fracture || d == Domain::Network || d == Domain::Fins) {
    // The sheets must be inside the volume (embedded), not on its boundary.
    gmsh::vectorpair bnd;
    gmsh::model::getBoundary(vols, bnd, false, false, false);
    if (bnd.size() != 6)
      throw std::logic_error(name_of(d) + ": the sheets were not embedded in the volume");
  }
}

// The elements of dimension count_dim (tets, or a layers domain's hexahedra
// and prisms, or a surface domain's triangles).
int count_dim(Domain d) { return d == Domain::Dfn ? 2 : 3; }

std::size_t count_elements(Domain d) {
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> tags, nodes;
  gmsh::model::mesh::getElements(types, tags, nodes, count_dim(d), -1);
  std::size_t n = 0;
  for (const auto& t : tags) n += t.size();
  return n;
}

void mesh_with_size(Domain d, double h) {
  gmsh::model::mesh::clear();
  // The layers domain grades from h/3 at the wall to h (its size field).
  const double h_min = d == Domain::Layers ? h / 3 : h;
  gmsh::option::setNumber("Mesh.MeshSizeMin", h_min);
  gmsh::option::setNumber("Mesh.MeshSizeMax", h);
  if (d == Domain::Layers) {
    gmsh::model::mesh::field::setNumber(kWallSizeField, "SizeMin", h_min);
    gmsh::model::mesh::field::setNumber(kWallSizeField, "SizeMax", h);
  }
  gmsh::model::mesh::generate(count_dim(d));
}

// Meshes the current model with about `target` elements (count_elements).
// Delaunay meshes with a uniform size h have about c·M/h^k elements (M the
// domain's measure, k its count_exponent); c depends on the algorithm and, for
// coarse meshes, on the boundary, and the count jumps whenever the number of
// segments on a model edge changes. So: measure c on a trial of at most
// kCalibration elements, then search h (secant on log n against log h,
// bisection once the target is bracketed) and keep the closest pass. Every
// step depends only on (domain, target), so the result is deterministic.
void mesh_to_target(Domain d, std::size_t target) {
  constexpr std::size_t kCalibration = 20000;
  // Elements per h^k, measured: Gmsh Delaunay tets; triangles of a Frontal-Delaunay
  // surface; the layers domain's kLayersNz prisms per triangle.
  const double initial_density = d == Domain::Dfn ? 2.3 : d == Domain::Layers ? 2.3 * kLayersNz : 7.0;
  const double M = domain_measure(d), k = count_exponent(d);
  const double goal_n = static_cast<double>(target);
  // cbrt and h*h*h for volumes: the tet domains' sizes, bit for bit as before.
  auto h_for = [M, k](double c, double n) { return k == 3 ? std::cbrt(c * M / n) : std::sqrt(c * M / n); };
  auto density = [M, k](double n, double h) { return k == 3 ? n * h * h * h / M : n * h * h / M; };

  // Trial for big targets: its density extrapolates well (boundary share shrinks).
  double c = initial_density;
  if (target > kCalibration) {
    const double h = h_for(c, kCalibration);
    mesh_with_size(d, h);
    c = density(static_cast<double>(count_elements(d)), h);
  }
  // Big meshes are costly to redo, so they get fewer passes and a looser
  // tolerance (the trial's density extrapolates to within ~10% there).
  const bool big = target > 200000;
  const int max_passes = big ? 2 : 8;
  const double tolerance = std::log(big ? 1.15 : 1.05);
  double best_h = 0, best_err = std::numeric_limits<double>::infinity();
  double lo_h = 0, hi_h = 0;  // h giving too many elements (small h) / too few (large h)
  double h = h_for(c, goal_n);
  double last_h = 0;
  for (int pass = 0; pass < max_passes; ++pass) {
    mesh_with_size(d, h);
    last_h = h;
    const double n = static_cast<double>(count_elements(d));
    if (n == 0) throw std::runtime_error(name_of(d) + ": gmsh produced no elements");
    const double err = std::abs(std::log(n / goal_n));
    if (err < best_err) best_err = err, best_h = h;
    if (best_err <= tolerance) break;
    if (n > goal_n) lo_h = h; else hi_h = h;
    c = density(n, h);
    double next = h_for(c, goal_n);
    // Once bracketed, stay strictly inside the bracket (the count is a step
    // function of h at coarse sizes, so the secant alone can cycle).
    if (lo_h > 0 && hi_h > 0 && (next <= lo_h || next >= hi_h || pass >= 3))
      next = std::sqrt(lo_h * hi_h);
    h = next;
  }
  if (last_h != best_h) mesh_with_size(d, best_h);
}

// The mesh as Gmsh holds it: all nodes, and the elements of every entity of
// dimension 3 (tets), 2 (triangles), 1 (segments) and 0 (points), entities in
// (dim, tag) order, highest dimension first.
void extract_raw(gmsh_module::RawMesh& out) {
  std::vector<double> param;
  gmsh::model::mesh::getNodes(out.node_tags, out.coords, param, -1, -1, false, false);
  constexpr int kElementType[] = {15, 1, 2, 4};  // point, segment, triangle, tet
  for (int dim = 3; dim >= 0; --dim) {
    gmsh::vectorpair entities;
    gmsh::model::getEntities(entities, dim);
    std::sort(entities.begin(), entities.end());
    for (auto [edim, tag] : entities) {
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> tags, nodes;
      gmsh::model::mesh::getElements(types, tags, nodes, edim, tag);
      gmsh_module::RawBlock block{dim, tag, {}};
      for (std::size_t i = 0; i < types.size(); ++i)
        if (types[i] == kElementType[dim]) block.nodes = std::move(nodes[i]);
      out.blocks.push_back(std::move(block));
    }
  }
}

// Renumbers the current mesh canonically: nodes by their coordinates,
// elements per (entity, type) by their nodes' new numbers (their node order
// kept). Gmsh's 2D boundary layers number the same mesh differently from run
// to run (measured: identical nodes and elements, node tags permuted), and
// the same domain must give the same file.
void canonical_numbering() {
  namespace mesh = gmsh::model::mesh;
  gmsh::vectorpair entities;
  gmsh::model::getEntities(entities);
  std::sort(entities.begin(), entities.end());
  struct Nodes {
    std::vector<std::size_t> tags;
    std::vector<double> coord, param;
  };
  std::vector<Nodes> nodes(entities.size());
  std::vector<std::pair<std::array<double, 3>, std::size_t>> order;
  for (std::size_t e = 0; e < entities.size(); ++e) {
    Nodes& n = nodes[e];
    mesh::getNodes(n.tags, n.coord, n.param, entities[e].first, entities[e].second, false, true);
    for (std::size_t i = 0; i < n.tags.size(); ++i)
      order.push_back({{n.coord[3 * i], n.coord[3 * i + 1], n.coord[3 * i + 2]}, n.tags[i]});
  }
  std::sort(order.begin(), order.end());
  std::size_t max_tag = 0;
  for (const auto& o : order) max_tag = std::max(max_tag, o.second);
  std::vector<std::size_t> renumbered(max_tag + 1, 0);
  for (std::size_t i = 0; i < order.size(); ++i) renumbered[order[i].second] = i + 1;
  struct Block {
    int tag, type;
    std::vector<std::vector<std::size_t>> elements;
  };
  std::vector<Block> blocks;
  for (auto [dim, tag] : entities) {
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> etags, enodes;
    mesh::getElements(types, etags, enodes, dim, tag);
    for (std::size_t t = 0; t < types.size(); ++t) {
      Block b{tag, types[t], {}};
      const std::size_t per = etags[t].empty() ? 0 : enodes[t].size() / etags[t].size();
      for (std::size_t k = 0; k < etags[t].size(); ++k) {
        std::vector<std::size_t> v(enodes[t].begin() + std::ptrdiff_t(k * per), enodes[t].begin() + std::ptrdiff_t((k + 1) * per));
        for (std::size_t& x : v) x = renumbered[x];
        b.elements.push_back(std::move(v));
      }
      std::sort(b.elements.begin(), b.elements.end());
      blocks.push_back(std::move(b));
    }
  }
  mesh::clear();
  for (std::size_t e = 0; e < entities.size(); ++e) {
    const Nodes& n = nodes[e];
    const std::size_t count = n.tags.size(), pdim = count ? n.param.size() / count : 0;
    std::vector<std::size_t> at(count);
    for (std::size_t i = 0; i < count; ++i) at[i] = i;
    std::sort(at.begin(), at.end(), [&](std::size_t a, std::size_t b) { return renumbered[n.tags[a]] < renumbered[n.tags[b]]; });
    std::vector<std::size_t> tags;
    std::vector<double> coord, param;
    for (std::size_t i : at) {
      tags.push_back(renumbered[n.tags[i]]);
      coord.insert(coord.end(), n.coord.begin() + std::ptrdiff_t(3 * i), n.coord.begin() + std::ptrdiff_t(3 * i + 3));
      param.insert(param.end(), n.param.begin() + std::ptrdiff_t(pdim * i), n.param.begin() + std::ptrdiff_t(pdim * (i + 1)));
    }
    mesh::addNodes(entities[e].first, entities[e].second, tags, coord, param);
  }
  std::size_t next = 1;
  for (const Block& b : blocks) {
    std::vector<std::size_t> etags, enodes;
    for (const auto& v : b.elements) {
      etags.push_back(next++);
      enodes.insert(enodes.end(), v.begin(), v.end());
    }
    mesh::addElementsByType(b.tag, b.type, etags, enodes);
  }
}

// Gmsh 4.8 keeps the attributes of a meshed extrusion (its ExtrudeParams,
// made in OCC_Internals::_setExtrudedAttributes and while the layers are
// meshed) past finalize(): LeakSanitizer reports about 10 kB for the layers
// domain (measured; an extrusion without layers and the other domains leak
// nothing). That memory is Gmsh's, so in a sanitizer build the layers
// domain's construction and meshing run with leak detection off; polydual's
// own code (canonical_numbering, the writer) runs outside it.
class GmshOwnedAllocations {
 public:
  explicit GmshOwnedAllocations(bool on) : on_(on) {
#if defined(__SANITIZE_ADDRESS__)
    if (on_) __lsan_disable();
#endif
  }
  ~GmshOwnedAllocations() {
#if defined(__SANITIZE_ADDRESS__)
    if (on_) __lsan_enable();
#endif
  }
  GmshOwnedAllocations(const GmshOwnedAllocations&) = delete;
  GmshOwnedAllocations& operator=(const GmshOwnedAllocations&) = delete;

 private:
  [[maybe_unused]] bool on_;
};

bool valid_domain(int domain, std::string& error) {
  if (domain >= 0 && domain < gmsh_module::kNumDomains) return true;
  error = "unknown domain number " + std::to_string(domain);
  return false;
}

bool mesh_entry(int domain, std::size_t target, gmsh_module::RawMesh& out, std::string& error) {
  if (!valid_domain(domain, error)) return false;
  const auto d = static_cast<Domain>(domain);
  if (d == Domain::Layers || d == Domain::Dfn) {
    error = name_of(d) + " is not a tet mesh: only its .msh file is written (write_msh)";
    return false;
  }
  try {
    GmshSession session;
    build_geometry(d);
    mesh_to_target(d, target);
    extract_raw(out);
    return true;
  } catch (...) {
    error = gmsh_error_message("meshing " + name_of(d));
    return false;
  }
}

bool write_msh_entry(int domain, std::size_t target, const char* path, std::string& error) {
  if (!valid_domain(domain, error)) return false;
  const auto d = static_cast<Domain>(domain);
  try {
    GmshSession session;
    {
      const GmshOwnedAllocations extrusion(d == Domain::Layers);
      build_geometry(d);
      mesh_to_target(d, target);
    }
    if (d == Domain::Layers) canonical_numbering();
    // SaveAll: without physical groups Gmsh writes everything anyway, but the
    // option makes that explicit and survives a later physical group.
    gmsh::option::setNumber("Mesh.SaveAll", 1);
    gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
    gmsh::option::setNumber("Mesh.Binary", 0);
    gmsh::write(path);
    return true;
  } catch (...) {
    error = gmsh_error_message(std::string("writing ") + path);
    return false;
  }
}

constexpr gmsh_module::GmshApi kApi{gmsh_module::kAbiVersion, mesh_entry, write_msh_entry};

}  // namespace

}  // namespace polydual

extern "C" __attribute__((visibility("default"))) const polydual::gmsh_module::GmshApi* polydual_gmsh_module_api() {
  return &polydual::kApi;
}
