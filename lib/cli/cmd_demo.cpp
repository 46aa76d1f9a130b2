// `demo`: the built-in run (no input file): generate the paper's domains,
// convert them (dual, exact check, optimisation), write VTU + OpenFOAM from
// the same mesh, re-read and re-check every VTU written, print a table.
#include <cstdio>
#include <filesystem>

#include "cli/commands.h"
#include "cli/print.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/stopwatch.h"
#include "generate/domains.h"
#include "io/output_guard.h"
#include "io/vtu_poly_reader.h"
#include "io/read_any_mesh.h"
#include "pipeline/convert.h"
#include "pipeline/convert_surface.h"
#include "pipeline/summary.h"

namespace polydual::cli {

const CommandSpec kDemo{
    "demo", "demo [--out DIR] [--tets N] [--domains LIST] [--optimize auto|none|untangle|local|global]",
    "Generates the paper's domains, a boundary-layer domain of hexahedra and prisms\n"
    "(layers) and a fracture network of triangles (dfn), builds and optimises their\n"
    "duals, writes DIR/<domain>.msh, DIR/<domain>.vtu, DIR/<domain>_case/ (OpenFOAM,\n"
    "volume domains) and DIR/summary.json, re-checks every polyhedral VTU written and\n"
    "prints a summary (elements: the input's tets, cells or triangles; cells: the\n"
    "dual's cells or polygons).",
    0, 0,
    {"--out", "--tets=20000", "--domains", "--optimize", "--force", "--threads", "--quiet"}};

namespace {

std::vector<Domain> parse_domains(const std::string& list) {
  std::vector<Domain> domains;
  for (std::size_t s = 0; s <= list.size();) {
    std::size_t e = list.find(',', s);
    if (e == std::string::npos) e = list.size();
    domains.push_back(parse_domain(list.substr(s, e - s)));
    s = e + 1;
  }
  return domains;
}

std::string val(const Json& j, const char* key) { return j.find(key) ? j.find(key)->dump(0) : "?"; }

// One row of the table: the input's elements (tets, mixed cells, triangles),
// the dual's cells (polygons) and faces, invalid cells before and after the
// optimiser, closed cells, the check, and the seconds.
void print_row(const std::string& name, const std::string& input, const std::string& cells, const std::string& faces,
               const std::string& invalid0, const std::string& invalid, const std::string& closed, const char* check,
               double seconds) {
  std::printf("%-9s %8s %8s %9s %8s %8s %7s %6s %8.2f\n", name.c_str(), input.c_str(), cells.c_str(), faces.c_str(),
              invalid0.c_str(), invalid.c_str(), closed.c_str(), check, seconds);
  std::fflush(stdout);
}

// A tet or mixed domain: convert, write the VTU and the case, re-check the VTU.
Json run_volume_domain(const std::string& name, const std::string& msh, const Settings& s,
                       const std::filesystem::path& dir, const Stopwatch& clock) {
  const std::string vtu = (dir / (name + ".vtu")).string();
  ProgressPrinter progress(s.quiet);
  const ConvertResult r = convert_file(msh, vtu, PolyFormat::Vtu, s.params, progress.hooks(), s.write);
  progress.end_line();
  Json j = convert_summary(r, s.params);
  j.set("foam", write_result(r, (dir / (name + "_case")).string(), PolyFormat::Foam, s.write));
  const PolyMesh back = read_vtu_poly(vtu);
  const CheckResult back_check = check_mesh(back, nullptr);
  const Json chk = mesh_summary(back, back_check, nullptr);
  j.set("recheck", chk);
  const bool same = val(chk, "invalid_cells") == val(j, "invalid_after") && val(chk, "cells") == val(j, "cells");
  // "FAIL": the validation of the dual or of the VTU read back found defects.
  const std::vector<Defect> defects = r.check.validation.defects(), back_defects = back_check.validation.defects();
  const bool sound = defects.empty() && back_defects.empty();
  const std::size_t input = r.mixed ? r.mixed->mesh.num_cells() : r.input_tets ? r.input_tets : r.primal.num_tets();
  print_row(name, std::to_string(input), val(j, "cells"), val(j, "faces"), val(j, "invalid_before"),
            val(j, "invalid_after"), val(j, "closed_cells"), !sound ? "FAIL" : same ? "ok" : "DIFF", clock.seconds());
  if (!defects.empty()) print_defects("demo", "warning", name + ": the dual is not sound:", defects);
  if (!back_defects.empty()) print_defects("demo", "warning", vtu + " read back is not sound:", back_defects);
  return j;
}

// A surface domain (design §15): the polygons of its dual, checked by the
// exact fan test and the area identity on its planar surfaces ("FAIL" when
// a polygon is invalid or the area identity misses by more than 1e-12).
Json run_surface_domain(const std::string& name, const std::string& msh, const Settings& s,
                        const std::filesystem::path& dir, const Stopwatch& clock) {
  const std::string vtu = (dir / (name + ".vtu")).string();
  ProgressPrinter progress(s.quiet);
  const SurfaceConvertResult r = convert_surface_file(read_any_mesh(msh), msh, vtu, "", surface_params(s.params),
                                                      s.write, progress.hooks());
  progress.end_line();
  Json j = surface_summary(r);
  const bool sound = r.verdicts.invalid == 0 && r.areas.max_rel_error <= 1e-12;
  print_row(name, std::to_string(r.primal.num_cells()), std::to_string(r.dual.num_polygons()), "-", "-",
            std::to_string(r.verdicts.invalid), "-", sound ? "ok" : "FAIL", clock.seconds());
  return j;
}

// One domain: generate its Gmsh file, then convert it as what it is.
Json run_domain(Domain d, const Settings& s, const std::filesystem::path& dir) {
  const Stopwatch clock;
  const std::string name = domain_name(d);
  const std::string msh = (dir / (name + ".msh")).string();
  write_domain_msh(d, static_cast<std::size_t>(s.tets), msh);
  const double gen = clock.seconds();
  Json j = domain_kind(d) == DomainKind::Surface ? run_surface_domain(name, msh, s, dir, clock)
                                                 : run_volume_domain(name, msh, s, dir, clock);
  j.set("domain", name);
  j.set("generate_seconds", gen);
  return j;
}

// Where the cells that stay invalid sit (paper §4: concave edges/corners and
// fracture tips), and how many are slit cells at fracture tips.
void print_remaining_invalid(const std::string& domain, const Json& j) {
  if (!j.find("invalid_after") || val(j, "invalid_after") == "0") return;
  const Json& by = *j.find("invalid_by_class");
  std::printf("%s: %s cells stay invalid: %s at model vertices, %s at model edges, %s on model faces, "
              "%s interior; %s slit cells (fracture tips)\n",
              domain.c_str(), val(j, "invalid_after").c_str(), val(by, "model_vertex").c_str(),
              val(by, "model_edge").c_str(), val(by, "model_face").c_str(), val(by, "interior").c_str(),
              val(j, "slit_cells").c_str());
}

// The names a demo writes into its directory, and the file that marks a
// directory as a demo's: a rerun replaces what an earlier demo wrote, and
// nothing else.
constexpr const char* kMarker = ".polydual-demo";
bool demo_name(const std::string& name) {
  if (name == kMarker || name == "summary.json") return true;
  for (const char* ext : {".msh", ".vtu", "_case"}) {
    const std::string e = ext;
    if (name.size() > e.size() && name.compare(name.size() - e.size(), e.size(), e) == 0) {
      try {
        parse_domain(name.substr(0, name.size() - e.size()));
        return true;
      } catch (const UsageError&) {
      }
    }
  }
  return false;
}

// The output directory must not exist (its parent must), be empty, or be an
// earlier demo's (the marker, and only names a demo writes); another one is
// refused unless --force, which still writes only the demo's names.
void prepare_out_dir(const std::filesystem::path& dir, bool force) {
  namespace fs = std::filesystem;
  const std::string shown = dir.string();
  if (!check_output_directory(shown)) {  // the shared rules: no link, no file, an existing parent
    fs::create_directory(dir);
  } else if (!force && !fs::is_empty(dir)) {
    const bool marked = fs::exists(fs::symlink_status(dir / kMarker));
    for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
      const std::string name = e.path().filename().string();
      if (!marked || !demo_name(name))
        throw UsageError("output directory '" + shown + "' holds '" + name + "', which " +
                         (marked ? "a demo does not write" : "is not from an earlier demo (no " + std::string(kMarker) +
                                                                 ")") +
                         "; choose an empty or new directory, or --force to write the demo's files beside it");
    }
  }
  write_file_atomically(dir / kMarker, [](std::ostream& os) {
    os << "written by polydual demo: a rerun replaces the demo's files here\n";
  });
}

}  // namespace

int cmd_demo(const Settings& s) {
  const std::filesystem::path dir = s.out_dir;
  const std::vector<Domain> domains = parse_domains(s.domains);
  s.params.validate();
  prepare_out_dir(dir, s.write.foam.force);
  Json all = Json::array();
  std::printf("%-9s %8s %8s %9s %8s %8s %7s %6s %8s\n", "domain", "elements", "cells", "faces", "invalid0",
              "invalid", "closed", "check", "seconds");
  for (Domain d : domains) all.push(run_domain(d, s, dir));
  for (std::size_t i = 0; i < domains.size(); ++i) print_remaining_invalid(domain_name(domains[i]), all.at(i));
  write_file_atomically(dir / "summary.json", [&](std::ostream& os) { os << all.dump() << "\n"; });
  std::printf("outputs in %s/ (open the .vtu files in ParaView; *_case/ are OpenFOAM cases)\n",
              dir.string().c_str());
  return 0;
}

}  // namespace polydual::cli
