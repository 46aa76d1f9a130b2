// Writes the CGAL Mesh_3 Medit files of tests/data (see CMakeLists.txt here
// for how to rebuild them): a two-material labelled ball, the unit ball cut by
// the plane x = 0.1 into subdomain 1 (x < 0.1) and subdomain 2, meshed once
// and written by CGAL::IO::output_to_medit with both show_patches values:
//   cgal_twomat_sides.mesh    show_patches = false (the default): every
//                             boundary and interface triangle twice with
//                             opposite orientations, refs the subdomains on
//                             its sides (an interface: 1 then 2; a boundary
//                             triangle: its subdomain twice);
//   cgal_twomat_patches.mesh  show_patches = true: each triangle once, with
//                             its surface patch number (3, 4, 5 here).
// 1404 tets, 695 boundary and interface triangles.
// Deterministic: CGAL's default random generator is seeded, meshing is
// sequential and the time-limited optimisers (perturb, exude) are off.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/File_medit.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/make_mesh_3.h>

#include <fstream>
#include <functional>
#include <iostream>
#include <string>

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Domain = CGAL::Labeled_mesh_domain_3<K>;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;

// 0 outside the unit ball, 1 and 2 on either side of the plane x = 0.1.
static int label(const Point& p) {
  if (p.x() * p.x() + p.y() * p.y() + p.z() * p.z() >= 1.0) return 0;
  return p.x() < 0.1 ? 1 : 2;
}

static bool write(const C3t3& c3t3, const std::string& path, bool show_patches) {
  std::ofstream out(path);
  CGAL::IO::output_to_medit(out, c3t3, /*rebind=*/false, show_patches);
  out.close();
  if (!out) std::cerr << path << ": cannot write\n";
  return bool(out);
}

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: mesh3_medit <output directory>\n";
    return 2;
  }
  CGAL::get_default_random() = CGAL::Random(0);
  namespace params = CGAL::parameters;
  const Domain domain(params::function = std::function<int(const Point&)>(label),
                      params::bounding_object = K::Sphere_3(CGAL::ORIGIN, 1.5 * 1.5),
                      params::relative_error_bound = 1e-6);
  const Criteria criteria(params::facet_angle = 25, params::facet_size = 0.3, params::facet_distance = 0.03,
                          params::cell_radius_edge_ratio = 3, params::cell_size = 0.3);
  const C3t3 c3t3 = CGAL::make_mesh_3<C3t3>(domain, criteria, params::no_perturb(), params::no_exude());
  std::cout << c3t3.number_of_cells_in_complex() << " tets, " << c3t3.number_of_facets_in_complex()
            << " boundary and interface triangles\n";
  const std::string dir = argv[1];
  return write(c3t3, dir + "/cgal_twomat_sides.mesh", false) && write(c3t3, dir + "/cgal_twomat_patches.mesh", true)
             ? 0 : 1;
}
