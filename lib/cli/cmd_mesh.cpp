// `generate` and `info`: the input side.
#include <cstdio>
#include <filesystem>

#include "cli/commands.h"
#include "cli/print.h"
#include "core/error.h"
#include "core/stopwatch.h"
#include "generate/domains.h"
#include "io/output_guard.h"
#include "classify/classify_primal.h"
#include "io/read_any_mesh.h"
#include "io/read_tet_mesh.h"
#include "mesh/cell_soup.h"
#include "io/write_tet_mesh.h"
#include "pipeline/summary.h"

namespace polydual::cli {

const CommandSpec kGenerate{
    "generate", "generate DOMAIN --tets N -o FILE [--threads N] [--quiet]",
    "Generates one of the demo domains (the paper's cube, twomat, fichera, fracture; the\n"
    "fracture network 'network'; the finned box 'fins'; the boundary layers of\n"
    "hexahedra and prisms 'layers' and the surface fracture network 'dfn', .msh only)\n"
    "with Gmsh, fully classified, deterministic (same N => same mesh). The output format\n"
    "follows FILE's extension: .msh (Gmsh 4.1, written by Gmsh), .mesh, .node, .vtu.\n"
    "Gmsh meshes serially (its parallel mesher is not deterministic); --threads\n"
    "bounds polydual's own work (classification, writers).",
    1, 1,
    {"--tets=10000", "-o", "--threads", "--quiet"}};

const CommandSpec kInfo{
    "info", "info FILE [--json] [--feature-angle DEG] [--strong-angle DEG] [--threads N] [--quiet]",
    "Reads and classifies a tet mesh; prints its size and its geometric model.",
    1, 1,
    {"--feature-angle", "--strong-angle", "--threads", "--json", "--quiet"}};

int cmd_generate(const Settings& s) {
  const Domain d = parse_domain(s.positional[0]);
  if (s.out.empty()) throw UsageError("generate needs -o FILE");
  check_output_target({}, s.out, OutputKind::File, false);
  const Stopwatch clock;
  const auto n = static_cast<std::size_t>(s.tets);
  if (std::filesystem::path(s.out).extension() == ".msh") write_domain_msh(d, n, s.out);
  else write_tet_mesh(generate_domain(d, n), s.out);
  if (!s.quiet)
    std::fprintf(stderr, "polydual: wrote %s (%s, target %lld tets) in %.2f s\n", s.out.c_str(),
                 domain_name(d).c_str(), s.tets, clock.seconds());
  return 0;
}

namespace {
void print_model(const std::string& path, const ClassifiedTetMesh& m, const Json& model) {
  std::printf("%s: %zu tets, %zu vertices, %zu triangles, %zu edges\n", path.c_str(), m.num_tets(),
              m.num_vertices(), m.num_triangles(), m.num_edges());
  std::printf("model: %zu vertices, %zu edges, %zu faces, %zu regions\n", m.model().count(0), m.model().count(1),
              m.model().count(2), m.model().count(3));
  const Json* faces = model.find("face_list");
  for (std::size_t i = 0; i < m.model().entities[2].size(); ++i) {
    const ModelEntity& f = m.model().entities[2][i];
    std::printf("  face %d: %s", f.tag, faces->at(i).find("kind")->dump(0).c_str());
    for (auto r : f.bounds) std::printf(" region %d", r);
    std::printf("\n");
  }
  // Per face marker: what the feature inference split and why (design §3).
  for (const MarkerFeatures& mf : m.marker_features()) {
    const std::string name = mf.marker ? "marker " + std::to_string(*mf.marker) : std::string("untagged");
    std::printf("  %s: %zu triangles -> %zu faces, %zu edges, %zu corners; %zu sharp edges: %zu strong and %zu in "
                "feature lines kept, %zu dropped as noise\n",
                name.c_str(), mf.facets, mf.model_faces, mf.model_edges, mf.corners, mf.sharp_edges, mf.strong_edges,
                mf.chain_edges, mf.noise_edges);
  }
}
}  // namespace

// A mixed or surface mesh: built as a primal (which checks orientation and
// conformity, exactly) and counted; `convert` makes its dual (a volume
// mesh's: pipeline/convert_mixed.h; a surface mesh's: pipeline/convert_surface.h).
int info_mixed(const Settings& s, const TetSoup& soup, Json seconds) {
  Stopwatch clock;
  std::vector<std::string> warnings;
  const PrimalMesh m = build_primal(cell_soup(soup), &warnings);
  seconds.set("primal", clock.seconds());
  print_warnings(warnings, s.quiet);
  const auto counts = mixed_cell_counts(soup);
  Json cells = Json::object();
  for (int t = 0; t < kNumCellTypes; ++t)
    if (counts[t]) cells.set(std::string(descriptor(CellType(t)).plural), counts[t]);
  Json j = Json::object();
  j.set("file", s.positional[0]);
  j.set("dimension", m.dim());
  j.set("cells", cells);
  j.set("vertices", m.num_vertices());
  j.set("faces", m.num_faces());
  j.set("edges", m.num_edges());
  j.set("ignored", ignored_summary(soup.ignored));
  j.set("seconds", seconds);
  if (s.json) {
    print_json(j);
  } else {
    std::printf("%s: a %s mesh: %s; %zu vertices, %zu faces, %zu edges (conformal%s)\n",
                s.positional[0].c_str(), m.dim() == 3 ? "mixed" : "surface", describe_cell_counts(counts).c_str(),
                m.num_vertices(), m.num_faces(), m.num_edges(), m.dim() == 3 ? ", every cell positively oriented" : "");
    std::printf(m.dim() == 3 ? "  `convert` makes its dual\n"
                             : "  `convert` builds its surface dual (polygons, VTU)\n");
  }
  return 0;
}

int cmd_info(const Settings& s) {
  const std::string& path = s.positional[0];
  s.params.validate();
  Json seconds = Json::object();
  Stopwatch clock;
  const TetSoup soup = read_any_mesh(path);
  seconds.set("read", clock.seconds());
  print_warnings(soup.warnings, s.quiet);
  if (is_mixed_or_surface(soup)) return info_mixed(s, soup, seconds);
  clock = Stopwatch();
  const ClassifiedTetMesh m = classify(soup, s.params.classify);
  seconds.set("classify", clock.seconds());
  print_warnings(m.classification_warnings(), s.quiet);
  const Json model = model_summary(m);
  Json j = Json::object();
  j.set("file", path);
  j.set("tets", m.num_tets());
  j.set("vertices", m.num_vertices());
  j.set("triangles", m.num_triangles());
  j.set("edges", m.num_edges());
  j.set("ignored", ignored_summary(soup.ignored));
  j.set("model", model);
  j.set("params", s.params.classify.to_json());
  j.set("seconds", seconds);
  if (s.json) print_json(j);
  else print_model(path, m, model);
  return 0;
}

}  // namespace polydual::cli
