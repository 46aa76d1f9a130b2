// A CGAL Mesh_3 mesh of a closed triangulated surface with its sharp features
// detected and protected (Polyhedral_mesh_domain_with_features_3), written as
// Medit the way CGAL's users get it by default (output_to_medit without
// patches: every boundary triangle carries the same pair of subdomains, so a
// reader must find the model's edges itself).
//
// The surface is read from IN (STL, OFF, OBJ or PLY) as a polygon soup,
// repaired, oriented consistently (Gmsh's STL keeps each OpenCASCADE face's
// own orientation, so neighbouring faces may disagree) and welded into one
// polyhedron oriented to bound its volume. It must be closed.
//
// Usage: polyhedral_features_medit IN OUT.mesh [key=value ...] with keys
// (defaults) angle (60: detect_features' dihedral angle in degrees),
// edge_size (0.05), facet_size (0.08), facet_distance (0.01),
// cell_size (0.08).
// Deterministic: CGAL's random generator is seeded, meshing is sequential and
// the time-limited optimisers (perturb, exude) are off.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/File_medit.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_polyhedron_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polyhedral_mesh_domain_with_features_3.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/make_mesh_3.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <vector>

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Polyhedron = CGAL::Mesh_polyhedron_3<K>::type;
using Domain = CGAL::Polyhedral_mesh_domain_with_features_3<K>;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr, Domain::Corner_index, Domain::Curve_index>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;

namespace {

struct Args {
  std::string in, out;
  double angle = 60, edge_size = 0.05, facet_size = 0.08, facet_distance = 0.01, cell_size = 0.08;
};

[[noreturn]] void usage(const std::string& why) {
  std::cerr << "polyhedral_features_medit: " << why
            << "\nusage: polyhedral_features_medit IN.stl|off OUT.mesh [angle=60] [edge_size=0.05]"
               " [facet_size=0.08] [facet_distance=0.01] [cell_size=0.08]\n";
  std::exit(2);
}

Args parse(int argc, char** argv) {
  if (argc < 3) usage("need an input surface and an output file");
  Args a;
  a.in = argv[1];
  a.out = argv[2];
  std::map<std::string, double*> number = {{"angle", &a.angle},
                                           {"edge_size", &a.edge_size},
                                           {"facet_size", &a.facet_size},
                                           {"facet_distance", &a.facet_distance},
                                           {"cell_size", &a.cell_size}};
  for (int i = 3; i < argc; ++i) {
    const std::string arg = argv[i];
    const std::size_t eq = arg.find('=');
    if (eq == std::string::npos) usage("'" + arg + "' is not key=value");
    const std::string key = arg.substr(0, eq);
    if (!number.count(key)) usage("unknown key '" + key + "'");
    *number[key] = std::atof(arg.c_str() + eq + 1);
  }
  if (!(a.angle > 0 && a.angle < 180)) usage("angle must be in (0, 180)");
  if (!(a.edge_size > 0) || !(a.facet_size > 0) || !(a.facet_distance > 0) || !(a.cell_size > 0))
    usage("sizes must be positive");
  return a;
}

// The closed surface of IN, or exit 1 naming the file and what is wrong.
Polyhedron read_surface(const std::string& path) {
  namespace PMP = CGAL::Polygon_mesh_processing;
  std::vector<K::Point_3> points;
  std::vector<std::vector<std::size_t>> polygons;
  if (!CGAL::IO::read_polygon_soup(path, points, polygons) || polygons.empty()) {
    std::cerr << path << ": cannot read polygons from this file\n";
    std::exit(1);
  }
  PMP::repair_polygon_soup(points, polygons);
  if (!PMP::orient_polygon_soup(points, polygons)) {
    std::cerr << path << ": the surface is not an orientable manifold (points were duplicated)\n";
    std::exit(1);
  }
  Polyhedron p;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, p);
  if (!CGAL::is_triangle_mesh(p) || !CGAL::is_closed(p)) {
    std::cerr << path << ": the surface is not a closed triangle mesh\n";
    std::exit(1);
  }
  PMP::orient_to_bound_a_volume(p);
  return p;
}

}  // namespace

int main(int argc, char** argv) {
  const Args a = parse(argc, argv);
  CGAL::get_default_random() = CGAL::Random(0);
  const Polyhedron surface = read_surface(a.in);
  Domain domain(surface);
  domain.detect_features(a.angle);
  namespace params = CGAL::parameters;
  const Criteria criteria(params::edge_size = a.edge_size, params::facet_angle = 25,
                          params::facet_size = a.facet_size, params::facet_distance = a.facet_distance,
                          params::cell_radius_edge_ratio = 3, params::cell_size = a.cell_size);
  const C3t3 c3t3 = CGAL::make_mesh_3<C3t3>(domain, criteria, params::no_perturb(), params::no_exude());
  std::ofstream out(a.out);
  CGAL::IO::output_to_medit(out, c3t3);
  out.close();
  if (!out) {
    std::cerr << a.out << ": cannot write\n";
    return 1;
  }
  std::cout << c3t3.number_of_cells_in_complex() << " tets, " << c3t3.number_of_facets_in_complex()
            << " boundary triangles, " << c3t3.number_of_edges_in_complex() << " feature edges\n";
  return 0;
}
