// The polyhedral writers, one class per format wrapping the format's own
// writer function, their registration (one line per format), and the lookups
// by name and by output path.
#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/error.h"
#include "io/format_registry.h"
#include "io/vtu_surface_writer.h"
#include "io/write_poly_mesh.h"

namespace polydual {

namespace {

class VtuPolyWriter final : public PolyWriter {
 public:
  std::string_view name() const override { return "vtu"; }
  std::string_view extension() const override { return ".vtu"; }
  OutputKind output_kind() const override { return OutputKind::File; }
  std::string_view help() const override { return "VTK XML file of VTK_POLYHEDRON cells (*.vtu)"; }
  void write(const PolyMesh& mesh, const std::string& path, const WriteContext& ctx, Json&) const override {
    write_vtu_poly(mesh, path, ctx.cell_fields, ctx.options.vtu, ctx.names);
  }
};

class FoamPolyWriter final : public PolyWriter {
 public:
  std::string_view name() const override { return "foam"; }
  std::string_view extension() const override { return ""; }
  OutputKind output_kind() const override { return OutputKind::FoamCase; }
  std::string_view help() const override {
    return "OpenFOAM case directory, OUT/constant/polyMesh (OUT without an extension)";
  }
  void write(const PolyMesh& mesh, const std::string& path, const WriteContext& ctx, Json& record) const override {
    record.set("foam", write_foam(mesh, path, ctx.options.foam, ctx.names).to_json());
  }
};

class VtuSurfaceWriter final : public SurfaceWriter {
 public:
  std::string_view name() const override { return "vtu"; }
  std::string_view extension() const override { return ".vtu"; }
  std::string_view help() const override { return "VTK XML file of VTK_POLYGON cells (*.vtu)"; }
  void write(const PolySurface& s, const std::string& path, const WriteContext& ctx, Json&) const override {
    write_vtu_surface(s, path, ctx.cell_fields, ctx.options.vtu);
  }
};

// constinit: constant-initialised, so usable from other files' static initialisers.
constinit const VtuPolyWriter kVtuWriter{};
constinit const FoamPolyWriter kFoamWriter{};
constinit const VtuSurfaceWriter kVtuSurfaceWriter{};

std::string joined(const std::vector<std::string>& parts, const char* sep) {
  std::string s;
  for (const std::string& p : parts) s += (s.empty() ? "" : sep) + p;
  return s;
}

}  // namespace

const std::vector<const PolyWriter*>& poly_writers() {
  static const std::vector<const PolyWriter*> all = {&kVtuWriter, &kFoamWriter};
  return all;
}

const std::vector<const SurfaceWriter*>& surface_writers() {
  static const std::vector<const SurfaceWriter*> all = {&kVtuSurfaceWriter};
  return all;
}

const SurfaceWriter& surface_writer_for(std::string_view requested, const std::string& path) {
  const std::string ext = lower_extension(path);
  std::vector<std::string> known;
  for (const SurfaceWriter* w : surface_writers()) {
    if (requested.empty() ? w->extension() == ext : w->name() == requested) return *w;
    known.push_back(std::string(w->name()) + " (" + std::string(w->extension()) + ")");
  }
  if (!requested.empty())
    throw UsageError("--format " + std::string(requested) + " cannot hold the dual of a surface mesh (polygons; " +
                     "surface formats: " + joined(known, ", ") + ")");
  throw UsageError("output '" + path + "': unsupported extension '" + ext + "' for the dual of a surface mesh (known: " +
                   joined(known, ", ") + ")");
}

std::string_view PolyFormat::name() const { return w_->name(); }

const PolyFormat PolyFormat::Vtu{kVtuWriter};
const PolyFormat PolyFormat::Foam{kFoamWriter};

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

const std::string& poly_format_choices() {
  static const std::string choices = [] {
    std::vector<std::string> names;
    for (const PolyWriter* w : poly_writers()) names.emplace_back(w->name());
    return joined(names, "|");
  }();
  return choices;
}

const std::string& poly_format_help() {
  static const std::string help = [] {
    std::vector<std::string> parts;
    for (const PolyWriter* w : poly_writers()) parts.push_back(std::string(w->name()) + ": " + std::string(w->help()));
    return "output format (default: from OUT's extension); " + joined(parts, "; ");
  }();
  return help;
}

const PolyWriter& poly_writer_named(std::string_view name) {
  for (const PolyWriter* w : poly_writers())
    if (w->name() == name) return *w;
  throw UsageError("unknown output format '" + std::string(name) + "' (known: " + poly_format_choices() + ")");
}

const PolyWriter& poly_writer_for_path(const std::string& path) {
  const std::string ext = !path.empty() && path.back() == '/' ? std::string() : lower_extension(path);
  std::vector<std::string> known;
  for (const PolyWriter* w : poly_writers()) {
    if (w->extension() == ext) return *w;
    known.push_back(w->extension().empty() ? "a directory without an extension (" + std::string(w->name()) + ")"
                                           : std::string(w->extension()) + " (" + std::string(w->name()) + ")");
  }
  throw UsageError("output '" + path + "': unsupported extension '" + ext + "' (known: " + joined(known, ", ") + ")");
}

PolyFormat parse_poly_format(std::string_view name) { return PolyFormat(poly_writer_named(name)); }

PolyFormat poly_format_for(std::string_view requested, const std::string& path) {
  if (!requested.empty()) return parse_poly_format(requested);
  return PolyFormat(poly_writer_for_path(path));
}

ModelNames model_names(const ModelTopology& model) {
  ModelNames names;
  for (const ModelEntity& r : model.entities[3])
    if (!r.name.empty()) names.regions.emplace(r.tag, r.name);
  for (const ModelEntity& f : model.entities[2])
    if (!f.name.empty()) names.faces.emplace(f.tag, f.name);
  return names;
}

Json write_poly_mesh(const PolyMesh& mesh, const std::string& path, PolyFormat format, const WriteContext& ctx) {
  Json rec = Json::object();
  rec.set("path", path);
  rec.set("format", std::string(format.name()));
  format.writer().write(mesh, path, ctx, rec);
  return rec;
}

Json write_poly_mesh(const PolyMesh& mesh, const std::string& path, PolyFormat format,
                     const std::vector<CellField>& cell_fields, const PolyWriteOptions& options) {
  return write_poly_mesh(mesh, path, format, WriteContext{options, cell_fields, {}});
}

}  // namespace polydual
