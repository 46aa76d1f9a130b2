// The tet mesh formats, one class per format wrapping the format's own
// reader and writer functions, and their registration (one line per format).
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

class GmshReader final : public MeshFormat {
 public:
  std::string_view name() const override { return "msh"; }
  // .gmsh2: the name Netgen proposes for its "Gmsh2 Format" export (msh 2.0).
  std::vector<std::string_view> extensions() const override { return {".msh", ".gmsh2"}; }
  std::string_view help() const override { return "Gmsh msh 2.0-2.2 and 4.1, ASCII or binary"; }
  TetSoup read(const std::string& path) const override { return read_msh_file(path); }
  void write(const TetSoup& soup, const std::string& path) const override { write_msh(soup, path); }
};

class MeditReader final : public MeshFormat {
 public:
  std::string_view name() const override { return "medit"; }
  std::vector<std::string_view> extensions() const override { return {".mesh"}; }
  std::string_view help() const override { return "Medit (INRIA) ASCII mesh"; }
  TetSoup read(const std::string& path) const override { return read_medit_file(path); }
  void write(const TetSoup& soup, const std::string& path) const override { write_medit(soup, path); }
};

class TetgenReader final : public MeshFormat {
 public:
  std::string_view name() const override { return "tetgen"; }
  std::vector<std::string_view> extensions() const override { return {".node", ".ele"}; }
  std::string_view help() const override { return "TetGen .node/.ele (and .face when present)"; }
  TetSoup read(const std::string& path) const override { return read_tetgen_files(path); }
  void write(const TetSoup& soup, const std::string& path) const override { write_tetgen(soup, path); }
};

class VtuReader final : public MeshFormat {
 public:
  std::string_view name() const override { return "vtu"; }
  std::vector<std::string_view> extensions() const override { return {".vtu"}; }
  std::string_view help() const override { return "VTK XML UnstructuredGrid of tetrahedra"; }
  TetSoup read(const std::string& path) const override { return read_vtu_file(path); }
  void write(const TetSoup& soup, const std::string& path) const override { write_vtu(soup, path); }
};

}  // namespace

const std::vector<const MeshFormat*>& mesh_formats() {
  static const GmshReader msh;
  static const MeditReader medit;
  static const TetgenReader tetgen;
  static const VtuReader vtu;
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
  if (const MeshFormat* f = mesh_format_of_extension(lower_extension(path))) return *f;
  const std::string ext = lower_extension(path);
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
