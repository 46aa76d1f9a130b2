// VTK itself (vtkXMLUnstructuredGridReader, /usr/bin/python3 with
// python3-vtk9) reads every format write_vtu_poly writes, the same mesh from
// each: tests/external/vtu_formats_check.py compares them with the ascii file.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "io/vtu_poly_reader.h"
#include "io/vtu_poly_writer.h"
#include "require_tool.h"

namespace polydual {
namespace {

namespace fs = std::filesystem;

TEST(IoVtuVtk, VtkReadsEveryWriterOption) {
  if (!test::have_python_module("vtk"))
    POLYDUAL_MISSING_TOOL("/usr/bin/python3 with vtk (python3-vtk9) is not installed");
  // The committed two-material hex pair (tests/data/poly_twomat_ascii.vtu).
  const PolyMesh m = read_vtu_poly(std::string(POLYDUAL_TEST_DATA) + "/poly_twomat_ascii.vtu");
  const fs::path dir = fs::temp_directory_path() / ("polydual_vtk_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::pair<const char*, VtuOptions> options[] = {
      {"ascii", {}},           {"binary", {true}},          {"binary_z1", {true, false, 1}},
      {"binary_z9", {true, false, 9}}, {"appended", {false, true, 0}}, {"appended_z6", {false, true, 6}}};
  std::string cmd = "/usr/bin/python3 '" POLYDUAL_SOURCE_DIR "/tests/external/vtu_formats_check.py'";
  const std::vector<CellField> extra{{"q", std::vector<double>(m.num_cells(), 0.25)}};
  for (const auto& [name, o] : options) {
    const fs::path p = dir / (std::string(name) + ".vtu");
    write_vtu_poly(m, p.string(), extra, o);
    cmd += " '" + p.string() + "'";
  }
  const fs::path log = dir / "check.log";
  const int rc = std::system((cmd + " > '" + log.string() + "' 2>&1").c_str());
  std::ifstream in(log);
  std::stringstream out;
  out << in.rdbuf();
  EXPECT_EQ(rc, 0) << out.str();
  EXPECT_NE(out.str().find("VTK reads 6 files"), std::string::npos) << out.str();
  std::error_code ec;
  fs::remove_all(dir, ec);
}

}  // namespace
}  // namespace polydual
