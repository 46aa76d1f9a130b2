// `generate` and `info`: the input side.
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "cli/commands.h"
#include "cli/pipeline.h"
#include "core/error.h"
#include "generate/domains.h"
#include "io/write_tet_mesh.h"

namespace polydual::cli {

const CommandSpec kGenerate{
    "generate", "generate DOMAIN --tets N -o FILE",
    "Generates one of the paper's domains (cube, twomat, fichera, fracture) with Gmsh,\n"
    "fully classified, deterministic (same N => same mesh). The output format follows\n"
    "FILE's extension: .msh (Gmsh 4.1, written by Gmsh), .mesh, .node, .vtu.",
    1, 1,
    {{"--tets", "N", "target number of tets (default 10000; result within ~30%)"},
     {"-o", "FILE", "output file (required)"}}};

const CommandSpec kInfo{
    "info", "info FILE [--json] [--feature-angle DEG]",
    "Reads and classifies a tet mesh; prints its size and its geometric model.",
    1, 1,
    {{"--json", "", "print one JSON object"},
     {"--feature-angle", "DEG", "dihedral angle that splits inferred model faces (default 30)"}}};

int cmd_generate(const Args& a) {
  const Domain d = parse_domain(a.positional[0]);
  const long long n = a.get_int("--tets", 10000);
  if (n < static_cast<long long>(kMinTargetTets) || n > static_cast<long long>(kMaxTargetTets))
    throw UsageError("--tets must be between " + std::to_string(kMinTargetTets) + " and " +
                     std::to_string(kMaxTargetTets));
  if (!a.has("-o")) throw UsageError("generate needs -o FILE");
  const std::string out = a.get("-o");
  Timer t;
  if (std::filesystem::path(out).extension() == ".msh") {
    write_domain_msh(d, static_cast<std::size_t>(n), out);
  } else {
    write_tet_mesh(generate_domain(d, static_cast<std::size_t>(n)), out);
  }
  std::fprintf(stderr, "polydual: wrote %s (%s, target %lld tets) in %.2f s\n", out.c_str(),
               domain_name(d).c_str(), n, t.seconds());
  return 0;
}

int cmd_info(const Args& a) {
  ClassifyParams cp;
  cp.feature_angle_deg = a.get_double("--feature-angle", cp.feature_angle_deg);
  Json seconds = Json::object();
  const std::string path = a.positional[0];
  ClassifiedTetMesh m = load_classified(path, cp, seconds);
  Json j = Json::object();
  j.set("file", path);
  j.set("tets", m.num_tets());
  j.set("vertices", m.num_vertices());
  j.set("triangles", m.num_triangles());
  j.set("edges", m.num_edges());
  j.set("model", model_summary(m));
  Json params = Json::object();
  params.set("feature_angle_deg", cp.feature_angle_deg);
  j.set("params", params);
  j.set("seconds", seconds);
  if (a.has("--json")) {
    std::cout << j.dump() << "\n";
  } else {
    std::printf("%s: %zu tets, %zu vertices, %zu triangles, %zu edges\n", path.c_str(), m.num_tets(),
                m.num_vertices(), m.num_triangles(), m.num_edges());
    std::printf("model: %zu vertices, %zu edges, %zu faces, %zu regions\n", m.model().count(0),
                m.model().count(1), m.model().count(2), m.model().count(3));
    for (const ModelEntity& f : m.model().entities[2]) {
      const char* kind = f.regions.size() < 2 ? "external" : (f.regions[0] == f.regions[1] ? "fracture" : "interface");
      std::printf("  face %d: %s", f.tag, kind);
      for (auto r : f.bounds) std::printf(" region %d", r);
      std::printf("\n");
    }
  }
  return 0;
}

}  // namespace polydual::cli
