// The formats polydual reads and writes, each one class and one registration
// line (io/mesh_formats.cpp, io/poly_writers.cpp). Everything the command
// says about formats comes from here: the `--format` values, the extensions
// that select a reader for an input and a writer for an output, the help text
// and the errors listing the known formats. A new format (Exodus II, CGNS, a
// decomposed case) is a new class and a new line in one of those two lists;
// the pipeline and the command do not change.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "core/json.h"
#include "io/output_guard.h"
#include "io/write_context.h"
#include "mesh/poly_mesh.h"
#include "mesh/poly_surface.h"
#include "mesh/tet_soup.h"

namespace polydual {

// One tet mesh format: read from a path, and written (generate, round trips).
class MeshFormat {
 public:
  virtual ~MeshFormat() = default;
  virtual std::string_view name() const = 0;  // "msh", "medit", ...
  // Lower-case, with the dot: {".msh", ".gmsh2"}. The first one is the
  // format's own; an input is read by the reader listing its extension.
  virtual std::vector<std::string_view> extensions() const = 0;
  virtual std::string_view help() const = 0;  // one line: what the format is
  // The reader's InputError (file and line/byte/record) for bad content.
  virtual TetSoup read(const std::string& path) const = 0;
  // Writes the soup's tets and classification atomically (the format's own
  // writer; std::runtime_error when the file cannot be written).
  virtual void write(const TetSoup& soup, const std::string& path) const = 0;
};

// Writes a polyhedral mesh in one format.
class PolyWriter {
 public:
  virtual ~PolyWriter() = default;
  virtual std::string_view name() const = 0;  // the `--format` value
  // ".vtu"; "" for a directory output (an OpenFOAM case), chosen for an
  // output name without an extension or ending in '/'.
  virtual std::string_view extension() const = 0;
  virtual OutputKind output_kind() const = 0;
  virtual std::string_view help() const = 0;  // one line: what is written
  // Writes atomically (no half-written output); adds the writer's own
  // fields to `record` (which holds "path" and "format").
  virtual void write(const PolyMesh& mesh, const std::string& path, const WriteContext& ctx,
                     Json& record) const = 0;
};

// Writes the polygon mesh of a surface dual (mesh/poly_surface.h).
class SurfaceWriter {
 public:
  virtual ~SurfaceWriter() = default;
  virtual std::string_view name() const = 0;       // the `--format` value
  virtual std::string_view extension() const = 0;  // ".vtu"
  virtual std::string_view help() const = 0;
  // Writes atomically; adds the writer's own fields to `record`.
  virtual void write(const PolySurface& surface, const std::string& path, const WriteContext& ctx,
                     Json& record) const = 0;
};

// All registered formats, in registration order.
const std::vector<const MeshFormat*>& mesh_formats();
const std::vector<const PolyWriter*>& poly_writers();
const std::vector<const SurfaceWriter*>& surface_writers();
// The surface writer for `--format` `requested` (empty: by `path`'s
// extension). UsageError when no surface writer has that name or extension
// (e.g. "foam": an OpenFOAM case holds volume cells), listing the known ones.
const SurfaceWriter& surface_writer_for(std::string_view requested, const std::string& path);

// The reader of `path`'s extension (case-insensitive). An unknown extension
// is an InputError naming the file and listing the known extensions (after
// the file itself was found readable, so a missing file is reported as such).
const MeshFormat& mesh_format_for(const std::string& path);
// The format of an extension (lower-case, with its dot), or null.
const MeshFormat* mesh_format_of_extension(std::string_view ext);
// The writer called `name`; UsageError listing the known names otherwise.
const PolyWriter& poly_writer_named(std::string_view name);
// The writer of an output path by its extension (see PolyWriter::extension);
// UsageError naming the path and listing the known extensions otherwise.
const PolyWriter& poly_writer_for_path(const std::string& path);

// "vtu|foam": the `--format` choices, in registration order.
const std::string& poly_format_choices();
// "vtu: ..., foam: ...": one clause per writer, for the option's help.
const std::string& poly_format_help();
// ".msh or .gmsh2, .mesh, .node or .ele, .vtu": the readable extensions.
std::string mesh_extensions_text();
// The lower-case extension of a path, with its dot ("" when none).
std::string lower_extension(const std::string& path);

}  // namespace polydual
