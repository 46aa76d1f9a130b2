// VTU files written by meshio at test time (/usr/bin/python3, Debian's
// python3-meshio): zlib-compressed binary (meshio's default), uncompressed
// binary and ascii; the region taken from each cell-data name meshio writes for
// other tools (gmsh:physical, medit:ref, CellEntityIds), the preference order
// when several are present, and Gmsh's vertex/line cells skipped.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "core/error.h"
#include "io/file_bytes.h"
#include "io/vtu_reader.h"
#include "require_tool.h"
#include "scratch_dir.h"

namespace polydual {
namespace {

namespace fs = std::filesystem;

bool have_meshio() {
  return test::have_python_module("meshio");
}

using test::scratch_dir;

// Writes the 5-tet unit cube with one triangle, one line and one vertex cell
// (Gmsh's lower-dimensional elements) with meshio: `cell_data` is Python
// source for the dict of cell-data arrays (one list per cell block).
fs::path meshio_write(const std::string& name, const std::string& write_args, const std::string& cell_data) {
  const fs::path dir = scratch_dir(), script = dir / (name + ".py"), out = dir / (name + ".vtu");
  std::ofstream(script) << "import meshio, numpy as np\n"
                           "pts = np.array([[v & 1, (v >> 1) & 1, (v >> 2) & 1] for v in range(8)], dtype=float)\n"
                           "tets = np.array([[0,1,2,4],[3,1,7,2],[5,1,4,7],[6,2,7,4],[1,2,4,7]])\n"
                           "cells = [('vertex', np.array([[0]])), ('line', np.array([[0, 1]])),\n"
                           "         ('triangle', np.array([[0, 1, 2]])), ('tetra', tets)]\n"
                           "m = meshio.Mesh(pts, cells, cell_data=" << cell_data << ")\n"
                           "meshio.write('" << out.string() << "', m" << write_args << ")\n";
  const std::string cmd = "/usr/bin/python3 '" + script.string() + "' 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  return out;
}

// Per block: vertex, line, triangle, tets.
std::string blocks(int vertex, int line, int tri, const std::string& tets) {
  return "[np.array([" + std::to_string(vertex) + "]), np.array([" + std::to_string(line) + "]), np.array([" +
         std::to_string(tri) + "]), np.array(" + tets + ")]";
}

void expect_cube(const TetSoup& s, const std::vector<std::int32_t>& regions, std::int32_t tri_tag) {
  ASSERT_EQ(s.points.size(), 8u);
  EXPECT_EQ(s.points[7].x, 1.0);
  ASSERT_EQ(s.tets.size(), 5u);
  EXPECT_EQ(s.tets[1], (std::array<std::uint32_t, 4>{3, 1, 7, 2}));
  EXPECT_EQ(s.tet_region, regions);
  ASSERT_EQ(s.triangles.size(), 1u);
  EXPECT_EQ(s.triangles[0].tag, tri_tag);
}

TEST(IoVtuMeshio, EveryMeshioEncodingAndRegionName) {
  if (!have_meshio()) POLYDUAL_MISSING_TOOL("/usr/bin/python3 with meshio (python3-meshio) is not installed");
  const std::string regions = "[10, 10, 10, 10, 20]";
  const std::vector<std::int32_t> expected{10, 10, 10, 10, 20};
  const std::pair<const char*, const char*> encodings[] = {
      {"zlib", ""}, {"raw", ", binary=True, compression=None"}, {"ascii", ", binary=False"}};
  for (const char* name : {"gmsh:physical", "medit:ref", "CellEntityIds"})
    for (const auto& [enc, args] : encodings) {
      SCOPED_TRACE(std::string(name) + " " + enc);
      const std::string stem = std::string(enc) + "_" + std::to_string(name[0]);
      const fs::path p = meshio_write(stem, args, "{'" + std::string(name) + "': " + blocks(1, 2, 7, regions) + "}");
      const std::string bytes = io::read_file_bytes(p.string());
      if (std::string(enc) == "zlib") EXPECT_NE(bytes.find("vtkZLibDataCompressor"), std::string::npos);
      if (std::string(enc) == "ascii") EXPECT_NE(bytes.find("format=\"ascii\""), std::string::npos);
      expect_cube(read_vtu_file(p.string()), expected, 7);
    }
}

TEST(IoVtuMeshio, RegionNamesInTheirDocumentedOrder) {
  if (!have_meshio()) POLYDUAL_MISSING_TOOL("/usr/bin/python3 with meshio (python3-meshio) is not installed");
  // medit:ref is preferred to CellEntityIds, gmsh:physical to medit:ref,
  // whatever order the file lists them in.
  const fs::path p = meshio_write("order", "", "{'CellEntityIds': " + blocks(0, 0, 3, "[3, 3, 3, 3, 3]") +
                                                   ", 'medit:ref': " + blocks(0, 0, 2, "[2, 2, 2, 2, 2]") + "}");
  expect_cube(read_vtu_file(p.string()), std::vector<std::int32_t>(5, 2), 2);
  const fs::path q = meshio_write("order2", "", "{'medit:ref': " + blocks(0, 0, 2, "[2, 2, 2, 2, 2]") +
                                                    ", 'gmsh:physical': " + blocks(0, 0, 1, "[1, 1, 1, 1, 4]") + "}");
  expect_cube(read_vtu_file(q.string()), {1, 1, 1, 1, 4}, 1);
  const fs::path none = meshio_write("none", "", "{}");
  expect_cube(read_vtu_file(none.string()), std::vector<std::int32_t>(5, 1), 0);
  std::error_code ec;
  fs::remove_all(scratch_dir(), ec);
}

}  // namespace
}  // namespace polydual
