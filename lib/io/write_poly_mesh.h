// Writing a PolyMesh in any registered format (io/format_registry.h), beside
// the reader dispatcher (read_tet_mesh.h). A format is picked by its
// `--format` name or by the output path; the pipeline and the command hold a
// PolyFormat and never branch on which one it is.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "core/json.h"
#include "io/write_context.h"
#include "mesh/poly_mesh.h"

namespace polydual {

class PolyWriter;

// A registered polyhedral output format: a handle to its writer.
class PolyFormat {
 public:
  constexpr explicit PolyFormat(const PolyWriter& w) : w_(&w) {}
  const PolyWriter& writer() const { return *w_; }
  std::string_view name() const;
  friend bool operator==(PolyFormat a, PolyFormat b) { return a.w_ == b.w_; }
  // The two formats as code names them (the registry has the full list).
  static const PolyFormat Vtu, Foam;

 private:
  const PolyWriter* w_;
};

// A registered format name ("vtu", "foam", ...); throws UsageError listing
// the known names.
PolyFormat parse_poly_format(std::string_view name);
// The format of an output path: the writer whose extension it has (*.vtu ->
// vtu; a name without an extension or ending in '/' -> foam, a case
// directory); any other extension is a UsageError listing the known ones (an
// output is never written under a name that says otherwise). A non-empty
// `requested` name wins over the path.
PolyFormat poly_format_for(std::string_view requested, const std::string& path);

// Writes `mesh` to `path` atomically with the context's cell fields (formats
// that take them) and model names; returns {"path", "format", and the
// writer's own record}.
Json write_poly_mesh(const PolyMesh& mesh, const std::string& path, PolyFormat format, const WriteContext& ctx);
// The same without model names.
Json write_poly_mesh(const PolyMesh& mesh, const std::string& path, PolyFormat format,
                     const std::vector<CellField>& cell_fields = {}, const PolyWriteOptions& options = {});

}  // namespace polydual
