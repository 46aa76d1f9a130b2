// convert_mesh IN [OUT]: polydual used as a library by another program.
// Reads a tet mesh (any format polydual reads: .msh, .mesh, .node/.ele, .vtu),
// runs the convert pipeline with its default parameters (the defaults of
// `polydual convert`), writes the polyhedral mesh when OUT is given (.vtu, or
// an OpenFOAM case directory), and prints the verdict: cell counts, invalid
// cells before/after optimisation (exact star test) and seconds per stage.
// Exit 0 on success, 1 on bad input, 2 on bad usage.
#include <cstdio>
#include <exception>
#include <string>

#include "core/error.h"
#include "io/read_tet_mesh.h"
#include "io/write_poly_mesh.h"
#include "pipeline/convert.h"

namespace {

void print_verdict(const std::string& in, const polydual::TetSoup& soup, const polydual::ConvertResult& r) {
  const polydual::ValidationReport& v = r.check.validation;
  std::printf("input %s: %zu tets, %zu vertices\n", in.c_str(), soup.tets.size(), soup.points.size());
  std::printf("cells %zu\n", r.mesh.num_cells());
  std::printf("faces %zu\n", v.faces);
  std::printf("closed_cells %zu\n", v.closed_cells);
  std::printf("invalid_before %zu\n", r.report.invalid_before);
  std::printf("invalid_after %zu\n", r.report.invalid_after);
  std::printf("valid %s\n", v.ok() && r.check.invalid_cells == 0 ? "yes" : "no");
  for (const polydual::StageRecord& s : r.report.stages) {
    std::printf("stage %-12s %.6f s\n", s.name.c_str(), s.seconds);
  }
  std::printf("seconds %.6f\n", r.report.seconds);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: %s IN [OUT]\n", argv[0]);
    return 2;
  }
  try {
    const std::string in = argv[1];
    const polydual::TetSoup soup = polydual::read_tet_mesh(in);
    const polydual::PipelineParams params;
    const polydual::ConvertResult r = polydual::convert(soup, params);
    if (argc == 3) {
      const std::string out = argv[2];
      polydual::write_result(r, out, polydual::poly_format_for("", out));
      std::printf("wrote %s\n", out.c_str());
    }
    print_verdict(in, soup, r);
    return 0;
  } catch (const polydual::UsageError& e) {
    std::fprintf(stderr, "convert_mesh: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {  // InputError names the file and the place
    std::fprintf(stderr, "convert_mesh: %s\n", e.what());
    return 1;
  }
}
