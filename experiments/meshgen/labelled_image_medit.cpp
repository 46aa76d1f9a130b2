// A three-material labelled image meshed by CGAL Mesh_3 and written as Medit
// (CGAL::IO::output_to_medit, every boundary and interface triangle once per
// side: the default that users of CGAL's image meshing get).
//
// The image: n^3 voxels over the unit cube, built in memory, label 1 the slab
// 0.25 <= z <= 0.60 and, by shape:
//   balls   label 2 the ball |p - (0.5 - r, 0.5, 0.60 + lift)| < r, label 3
//           the ball |p - (0.5 + r, 0.5, 0.60 + lift)| < r: they stick out of
//           the slab's top and touch each other at (0.5, 0.5, 0.60 + lift);
//           with lift > 0 above the slab, the outside on both sides of the
//           contact;
//   blocks  on the slab, label 2 the block x, y < 0.5 and label 3 the block
//           x, y > 0.5 (0.60 <= z <= 0.85): diagonal neighbours, touching
//           along the line x = y = 0.5 between two wedges of outside;
// label 0 elsewhere (outside). Three materials and the outside meet along
// curves and at points; where Mesh_3 leaves two materials touching along an
// edge or at a vertex with the outside on both sides, the mesh is not a
// manifold there (proofs/edge_chains.md), which a polyhedral dual must keep
// closed.
//
// Usage: labelled_image_medit OUT.mesh [key=value ...] with keys (defaults)
//   shape (balls), n (64), r (0.22), lift (0.05), facet_size (0.05),
//   cell_size (0.05), facet_distance (0.01).
// Deterministic: CGAL's random generator is seeded, meshing is sequential and
// the time-limited optimisers (perturb, exude) are off.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/File_medit.h>
#include <CGAL/Image_3.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/make_mesh_3.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <string>

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Domain = CGAL::Labeled_mesh_domain_3<K>;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;

namespace {

struct Args {
  std::string out, shape = "balls";
  int n = 64;
  double r = 0.22, lift = 0.05, facet_size = 0.05, cell_size = 0.05, facet_distance = 0.01;
};

constexpr double kSlabBottom = 0.25, kSlabTop = 0.60, kBlockTop = 0.85;

// The label at p (see the file comment).
unsigned char label(const Args& a, double x, double y, double z) {
  if (a.shape == "balls") {
    auto in_ball = [&](double cx) {
      const double dx = x - cx, dy = y - 0.5, dz = z - kSlabTop - a.lift;
      return dx * dx + dy * dy + dz * dz < a.r * a.r;
    };
    if (in_ball(0.5 - a.r)) return 2;
    if (in_ball(0.5 + a.r)) return 3;
  } else if (z > kSlabTop && z <= kBlockTop) {
    if (x < 0.5 && y < 0.5) return 2;
    if (x > 0.5 && y > 0.5) return 3;
  }
  return z >= kSlabBottom && z <= kSlabTop ? 1 : 0;
}

// An n^3 image of 8-bit labels with voxel size 1/n, sampled at the voxel
// centres (the image's origin is the first voxel's centre, as CGAL's image
// domains take it).
CGAL::Image_3 make_image(const Args& a) {
  const int n = a.n;
  const double h = 1.0 / n;
  _image* im = _createImage(n, n, n, 1, h, h, h, 1, WK_FIXED, SGN_UNSIGNED);
  auto* data = static_cast<unsigned char*>(im->data);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        data[(std::size_t(k) * n + j) * n + i] = label(a, (i + 0.5) * h, (j + 0.5) * h, (k + 0.5) * h);
  return CGAL::Image_3(im);
}

[[noreturn]] void usage(const std::string& why) {
  std::cerr << "labelled_image_medit: " << why
            << "\nusage: labelled_image_medit OUT.mesh [shape=balls|blocks] [n=64] [r=0.22] [lift=0.05]"
               " [facet_size=0.05] [cell_size=0.05] [facet_distance=0.01]\n";
  std::exit(2);
}

Args parse(int argc, char** argv) {
  if (argc < 2) usage("no output file");
  Args a;
  a.out = argv[1];
  std::map<std::string, double*> number = {{"r", &a.r},
                                           {"lift", &a.lift},
                                           {"facet_size", &a.facet_size},
                                           {"cell_size", &a.cell_size},
                                           {"facet_distance", &a.facet_distance}};
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    const std::size_t eq = arg.find('=');
    if (eq == std::string::npos) usage("'" + arg + "' is not key=value");
    const std::string key = arg.substr(0, eq), value = arg.substr(eq + 1);
    if (key == "shape") a.shape = value;
    else if (key == "n") a.n = std::atoi(value.c_str());
    else if (number.count(key)) *number[key] = std::atof(value.c_str());
    else usage("unknown key '" + key + "'");
  }
  if (a.shape != "balls" && a.shape != "blocks") usage("shape must be balls or blocks");
  if (a.n < 8 || a.n > 1024) usage("n must be in [8, 1024]");
  if (!(a.r > 0 && a.r < 0.25) || !(a.lift >= 0 && a.lift < a.r)) usage("need 0 < r < 0.25 and 0 <= lift < r");
  if (!(a.facet_size > 0) || !(a.cell_size > 0) || !(a.facet_distance > 0)) usage("sizes must be positive");
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  const Args a = parse(argc, argv);
  CGAL::get_default_random() = CGAL::Random(0);
  const CGAL::Image_3 image = make_image(a);
  namespace params = CGAL::parameters;
  const Domain domain = Domain::create_labeled_image_mesh_domain(image, params::relative_error_bound = 1e-6);
  const Criteria criteria(params::facet_angle = 30, params::facet_size = a.facet_size,
                          params::facet_distance = a.facet_distance, params::cell_radius_edge_ratio = 3,
                          params::cell_size = a.cell_size);
  const C3t3 c3t3 = CGAL::make_mesh_3<C3t3>(domain, criteria, params::no_perturb(), params::no_exude());
  std::ofstream out(a.out);
  CGAL::IO::output_to_medit(out, c3t3, /*rebind=*/false, /*show_patches=*/false);
  out.close();
  if (!out) {
    std::cerr << a.out << ": cannot write\n";
    return 1;
  }
  std::cout << c3t3.number_of_cells_in_complex() << " tets, " << c3t3.number_of_facets_in_complex()
            << " boundary and interface triangles\n";
  return 0;
}
