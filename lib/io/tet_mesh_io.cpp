// The extension dispatch of write_tet_mesh.h (reading goes through the
// format registry, io/format_registry.h).
#include "core/error.h"
#include "io/format_registry.h"
#include "io/medit_io.h"
#include "io/msh_reader.h"
#include "io/msh_writer.h"
#include "io/tetgen_io.h"
#include "io/vtu_reader.h"
#include "io/vtu_writer.h"
#include "io/write_tet_mesh.h"

namespace polydual {

void write_tet_mesh(const TetSoup& soup, const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".msh") return write_msh(soup, path);
  if (ext == ".mesh") return write_medit(soup, path);
  if (ext == ".node" || ext == ".ele") return write_tetgen(soup, path);
  if (ext == ".vtu") return write_vtu(soup, path);
  throw UsageError(path + ": unknown mesh file extension '" + ext + "' (supported: .msh, .mesh, .node/.ele, .vtu)");
}

}  // namespace polydual
