// The extension dispatch of read_tet_mesh.h and write_tet_mesh.h.
#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/error.h"
#include "io/file_bytes.h"
#include "io/medit_io.h"
#include "io/msh_reader.h"
#include "io/msh_writer.h"
#include "io/read_tet_mesh.h"
#include "io/tetgen_io.h"
#include "io/vtu_reader.h"
#include "io/vtu_writer.h"
#include "io/write_tet_mesh.h"

namespace polydual {

static std::string extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

TetSoup read_tet_mesh(const std::string& path) {
  const std::string ext = extension(path);
  // .gmsh2: the name Netgen proposes for its "Gmsh2 Format" export (msh 2.0).
  if (ext == ".msh" || ext == ".gmsh2") return read_msh_file(path);
  if (ext == ".mesh") return read_medit_file(path);
  if (ext == ".node" || ext == ".ele") return read_tetgen_files(path);
  if (ext == ".vtu") return read_vtu_file(path);
  io::require_regular_file(path);  // a missing file or a device is reported as such first
  throw InputError(path, "", "unknown mesh file extension '" + ext +
                                 "' (supported: .msh or .gmsh2, .mesh, .node/.ele, .vtu)");
}

void write_tet_mesh(const TetSoup& soup, const std::string& path) {
  const std::string ext = extension(path);
  if (ext == ".msh") return write_msh(soup, path);
  if (ext == ".mesh") return write_medit(soup, path);
  if (ext == ".node" || ext == ".ele") return write_tetgen(soup, path);
  if (ext == ".vtu") return write_vtu(soup, path);
  throw UsageError(path + ": unknown mesh file extension '" + ext + "' (supported: .msh, .mesh, .node/.ele, .vtu)");
}

}  // namespace polydual
