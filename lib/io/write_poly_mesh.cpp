#include "io/write_poly_mesh.h"

#include <filesystem>

#include "core/error.h"

namespace polydual {

const char* poly_format_name(PolyFormat f) { return f == PolyFormat::Vtu ? "vtu" : "foam"; }

PolyFormat parse_poly_format(std::string_view name) {
  if (name == "vtu") return PolyFormat::Vtu;
  if (name == "foam") return PolyFormat::Foam;
  throw UsageError("output format must be vtu or foam, not '" + std::string(name) + "'");
}

PolyFormat poly_format_for(std::string_view requested, const std::string& path) {
  if (!requested.empty()) return parse_poly_format(requested);
  if (!path.empty() && path.back() == '/') return PolyFormat::Foam;
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".vtu") return PolyFormat::Vtu;
  if (ext.empty()) return PolyFormat::Foam;
  throw UsageError("output '" + path + "': unsupported extension '" + ext +
                   "' (polyhedral outputs are .vtu files or OpenFOAM case directories without an extension)");
}

Json write_poly_mesh(const PolyMesh& mesh, const std::string& path, PolyFormat format,
                     const std::vector<CellField>& cell_fields, const PolyWriteOptions& options) {
  Json rec = Json::object();
  rec.set("path", path);
  rec.set("format", poly_format_name(format));
  if (format == PolyFormat::Foam) {
    rec.set("foam", write_foam(mesh, path, options.foam).to_json());
  } else {
    write_vtu_poly(mesh, path, cell_fields, options.vtu);
  }
  return rec;
}

}  // namespace polydual
