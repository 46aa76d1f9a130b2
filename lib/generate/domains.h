// The paper's demo domains (Garimella, Kim & Berndt 2013, section 4), meshed by
// Gmsh (OpenCASCADE kernel, 3D Delaunay) so the tool runs without an input file.
// Every mesh carries full classification: region tag per tet, model face tag per
// boundary/interface/fracture triangle, model edge tag per curve segment, model
// vertex tag per corner node.
//
// Determinism: the same (domain, target_tets) gives the same mesh, byte for byte,
// on every run (Gmsh single-threaded, fixed random seed, no user config files).
#pragma once
#include <cstddef>
#include <string>

#include "mesh/tet_soup.h"

namespace polydual {

enum class Domain {
  Cube,      // unit box [0,1]^3 (paper Fig. 7)
  TwoMat,    // box [0,2]x[0,1]x[0,1] cut at x=1 into regions 1 (x<1) and 2 (x>1)
  Fichera,   // [0,1]^3 minus the octant [0.5,1]^3: 3 re-entrant edges, 1 re-entrant corner
  Fracture,  // unit box with an embedded zero-thickness rectangle at z=0.5,
             // x in [0,0.6], y in [0.2,0.8] (touches the wall x=0, has 3 free edges)
  Network,   // unit box with three mutually crossing rectangles (fracture network):
             // z=0.5 (x in [0,0.7], y in [0.2,0.8], meets the wall x=0),
             // y=0.5 (x in [0.3,0.9], z in [0.2,0.8]) and x=0.5 (y in [0.25,0.75],
             // z in [0.3,0.7]), both ending inside; the three intersection lines
             // meet at the point (0.5,0.5,0.5)
  Fins,      // unit box with three fins, zero-thickness rectangles attached to a
             // wall along a line and ending inside: y=0.5 from x=0 (x in [0,0.4],
             // z in [0.2,0.8]), z=0.5 from x=1 (x in [0.6,1], y in [0.2,0.8]) and
             // x=0.5 from y=1 (y in [0.65,1], z in [0.25,0.75])
  Layers,    // a mixed mesh (design §14): a channel [-2,4]x[-1.5,1.5] around a
             // cylinder of radius 0.5, extruded over z in [0,0.4] in 4 layers,
             // with hexahedral boundary layers on the cylinder's wall (first
             // layer 0.01 thick, ratio 1.3) and prisms elsewhere
  Dfn,       // a surface mesh (design §15): the network's three rectangles on
             // their own, a discrete fracture network of triangles crossing
             // along lines
};

// What a domain's mesh is made of: tets, mixed volume cells, or surface cells.
enum class DomainKind { Tets, Mixed, Surface };
DomainKind domain_kind(Domain d);

// "cube" | "twomat" | "fichera" | "fracture" | "network" | "fins" | "layers" |
// "dfn"; throws UsageError listing these.
Domain parse_domain(const std::string& name);
std::string domain_name(Domain d);

// Smallest and largest accepted target_tets (UsageError outside).
inline constexpr std::size_t kMinTargetTets = 100;
inline constexpr std::size_t kMaxTargetTets = 20'000'000;

// Meshes tet domain d with about target_tets tetrahedra (within ~10-30%), all
// positively oriented, full_classification = true. Throws UsageError on a bad
// target or a domain that is not of kind Tets (write its .msh instead), and
// std::runtime_error when Gmsh fails.
TetSoup generate_domain(Domain d, std::size_t target_tets);

// The same mesh written by Gmsh's own msh 4.1 ASCII writer (all elements, with
// $Entities), atomically: a temporary "<path>.tmp.<pid>.msh" renamed to path.
// Every domain; target_tets counts the layers domain's volume cells and the
// dfn domain's triangles.
void write_domain_msh(Domain d, std::size_t target_tets, const std::string& path);

}  // namespace polydual
