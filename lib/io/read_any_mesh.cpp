// read_any_mesh: the surface-mesh entry beside read_tet_mesh's dispatch.
#include "io/read_any_mesh.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "io/msh_reader.h"
#include "io/read_tet_mesh.h"

namespace polydual {

TetSoup read_any_mesh(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".msh" || ext == ".gmsh2") return read_msh_file(path, /*surfaces=*/true);
  return read_tet_mesh(path);
}

}  // namespace polydual
