// The tet mesh formats, each its reader and writer functions wrapped in a
// MeshFormat, and their registration (one line per format).
#include <utility>

#include "core/error.h"
#include "io/file_bytes.h"
#include "io/format_registry.h"
#include "io/medit_io.h"
#include "io/msh_reader.h"
#include "io/msh_writer.h"
#include "io/read_tet_mesh.h"
#include "io/tetgen_io.h"
#include "io/vtu_reader.h"
#include "io/vtu_writer.h"
#include "io/write_tet_mesh.h"

namespace polydual {

namespace {

// A format whose reader and writer are free functions (every tet format so
// far; a format with state of its own derives from MeshFormat instead).
class FunctionFormat final : public MeshFormat {
 public:
  using Read = TetSoup (*)(const std::string&);
  using Write = void (*)(const TetSoup&, const std::string&);
  FunctionFormat(std::string_view name, std::vector<std::string_view> extensions, std::string_view help, Read read,
                 Write write)
      : name_(name), extensions_(std::move(extensions)), help_(help), read_(read), write_(write) {}
  std::string_view name() const override { return name_; }
  std::vector<std::string_view> extensions() const override { return extensions_; }
  std::string_view help() const override { return help_; }
  TetSoup read(const std::string& path) const override { return read_(path); }
  void write(const TetSoup& soup, const std::string& path) const override { write_(soup, path); }

 private:
  std::string_view name_;
  std::vector<std::string_view> extensions_;
  std::string_view help_;
  Read read_;
  Write write_;
};

}  // namespace

const std::vector<const MeshFormat*>& mesh_formats() {
  // .gmsh2: the name Netgen proposes for its "Gmsh2 Format" export (msh 2.0).
  static const FunctionFormat msh{"msh", {".msh", ".gmsh2"}, "Gmsh msh 2.0-2.2 and 4.1, ASCII or binary",
                                  [](const std::string& path) { return read_msh_file(path); }, write_msh};
  static const FunctionFormat medit{"medit", {".mesh"}, "Medit (INRIA) ASCII mesh", read_medit_file, write_medit};
  static const FunctionFormat tetgen{"tetgen", {".node", ".ele"}, "TetGen .node/.ele (and .face when present)",
                                     read_tetgen_files, write_tetgen};
  static const FunctionFormat vtu{"vtu", {".vtu"}, "VTK XML UnstructuredGrid of tetrahedra", read_vtu_file, write_vtu};
  static const std::vector<const MeshFormat*> all = {&msh, &medit, &tetgen, &vtu};
  return all;
}

const MeshFormat* mesh_format_of_extension(std::string_view ext) {
  for (const MeshFormat* r : mesh_formats())
    for (std::string_view e : r->extensions())
      if (e == ext) return r;
  return nullptr;
}

const MeshFormat& mesh_format_for(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (const MeshFormat* f = mesh_format_of_extension(ext)) return *f;
  io::require_regular_file(path);  // a missing file or a device is reported as such first
  throw InputError(path, "", "unknown mesh file extension '" + ext + "' (supported: " + mesh_extensions_text() + ")");
}

std::string mesh_extensions_text() {
  std::string text;
  for (const MeshFormat* r : mesh_formats()) {
    if (!text.empty()) text += ", ";
    const auto exts = r->extensions();
    for (std::size_t i = 0; i < exts.size(); ++i) text += (i ? " or " : "") + std::string(exts[i]);
  }
  return text;
}

TetSoup read_tet_mesh(const std::string& path) { return mesh_format_for(path).read(path); }

void write_tet_mesh(const TetSoup& soup, const std::string& path) {
  const std::string ext = lower_extension(path);
  const MeshFormat* f = mesh_format_of_extension(ext);
  if (!f) throw UsageError(path + ": unknown mesh file extension '" + ext + "' (supported: " + mesh_extensions_text() + ")");
  f->write(soup, path);
}

}  // namespace polydual
