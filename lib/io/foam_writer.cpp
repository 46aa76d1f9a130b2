#include "io/foam_writer.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <filesystem>
#include <memory>
#include <map>
#include <set>
#include <cctype>
#include <span>
#include <ostream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "io/output_guard.h"

namespace polydual {

Json FoamReport::to_json() const {
  Json j = Json::object();
  j.set("points", points);
  j.set("cells", cells);
  j.set("faces", faces);
  j.set("internal_faces", internal_faces);
  j.set("patches", patches);
  j.set("cell_zones", cell_zones);
  j.set("face_zones", face_zones);
  j.set("slit_faces", slit_faces);
  j.set("dropped_points", dropped_points);
  j.set("faces_without_spurs", faces_without_spurs);
  j.set("dropped_degenerate_faces", dropped_degenerate_faces);
  return j;
}

namespace {

namespace fs = std::filesystem;
using Label = std::int64_t;

// A face as OpenFOAM will see it.
struct OutFace {
  FaceId source;
  Label owner = -1, neighbour = -1;  // neighbour -1 on the boundary
  bool flipped = false;              // loop reversed w.r.t. the PolyMesh
  std::vector<PointId> loop;         // as OpenFOAM gets it (flipped, spurs removed)
};

// The loop without spurs: "a b a" (out to b and straight back) and repeated
// "a a". OpenFOAM rejects a face that lists a point twice; a spur encloses no
// area and its two edge uses cancel within the face, so removing it changes
// neither the face's area vector nor any cell's closedness. The dual has such
// faces where a cap passes twice through the midpoint of a model edge (e.g.
// around the corner where a fracture's free edge meets a wall). Other repeats
// (a loop pinched into two lobes) are left for checkMesh to report.
std::vector<PointId> without_spurs(std::span<const PointId> face) {
  std::vector<PointId> loop(face.begin(), face.end());
  for (bool changed = true; changed && loop.size() >= 3;) {
    changed = false;
    const std::size_t n = loop.size();
    for (std::size_t i = 0; i < n && !changed; ++i) {
      const std::size_t next = (i + 1) % n, prev = (i + n - 1) % n;
      if (loop[i] == loop[next]) {  // "a a"
        loop.erase(loop.begin() + static_cast<long>(i));
        changed = true;
      } else if (loop[prev] == loop[next]) {  // "a b a": drop b and one a
        const std::size_t hi = std::max(i, next), lo = std::min(i, next);
        loop.erase(loop.begin() + static_cast<long>(hi));
        loop.erase(loop.begin() + static_cast<long>(lo));
        changed = true;
      }
    }
  }
  return loop;
}

struct Patch { std::string name; Label start = 0, size = 0; };
struct FaceZone { std::string name; std::vector<Label> faces; std::vector<bool> flip; };

// The whole case in OpenFOAM numbering, computed before touching the disk.
struct FoamCase {
  std::vector<Label> point_map;  // PolyMesh point -> OpenFOAM point, -1 if dropped
  std::vector<PointId> points;   // OpenFOAM point -> PolyMesh point
  std::vector<OutFace> faces;
  Label internal = 0;
  std::vector<Patch> patches;
  std::vector<std::pair<std::string, std::vector<Label>>> cell_zones;  // (name, cells)
  std::vector<FaceZone> face_zones;
};

// A model name as an OpenFOAM word (a patch or zone name): letters, digits,
// '_', '.' and '-' are kept, any other byte becomes '_', and a word that
// would not start with a letter or '_' (OpenFOAM would read a number) gets a
// leading '_'.
std::string foam_word(const std::string& name) {
  std::string w;
  for (unsigned char c : name) w += std::isalnum(c) || c == '_' || c == '.' || c == '-' ? char(c) : '_';
  if (w.empty() || !(std::isalpha(static_cast<unsigned char>(w[0])) || w[0] == '_')) w.insert(w.begin(), '_');
  return w;
}

// Words for model names, unique: one model name gets one word, two names
// that sanitise alike get "_2", "_3", ... appended, and no word takes one of
// the `reserved` names (the "face_<tag>" names of unnamed entities).
class WordNamer {
 public:
  explicit WordNamer(std::set<std::string> reserved) : used_(std::move(reserved)) {}
  const std::string& word(const std::string& name) {
    if (auto it = of_.find(name); it != of_.end()) return it->second;
    std::string w = foam_word(name);
    for (int n = 2; used_.count(w); ++n) w = foam_word(name) + "_" + std::to_string(n);
    used_.insert(w);
    return of_.emplace(name, w).first->second;
  }

 private:
  std::set<std::string> used_;
  std::map<std::string, std::string> of_;
};

// The name of each key: its model name's word, else `fallback(key)`.
template <class Key, class Named, class Fallback>
std::map<Key, std::string> names_of(const std::vector<Key>& keys, Named named, Fallback fallback) {
  std::set<std::string> reserved;
  for (const Key& k : keys)
    if (!named(k)) reserved.insert(fallback(k));
  WordNamer namer(std::move(reserved));
  std::map<Key, std::string> out;
  for (const Key& k : keys) out.emplace(k, named(k) ? namer.word(*named(k)) : fallback(k));
  return out;
}

const std::string* name_in(const std::map<std::int32_t, std::string>& names, std::int32_t tag) {
  const auto it = names.find(tag);
  return it == names.end() ? nullptr : &it->second;
}

using BoundaryKey = std::pair<int, std::int32_t>;  // (0, model face tag) or (1, 0): defaultFaces

// The patches in key order, those of one model name merged into one (at the
// place of its first tag): "face_<tag>" without a name, "defaultFaces" for
// faces that are not External.
void add_patches(FoamCase& fc, std::map<BoundaryKey, std::vector<OutFace>>& boundary, const ModelNames& names) {
  std::vector<BoundaryKey> keys;
  for (const auto& [key, list] : boundary) keys.push_back(key);
  const auto name = names_of(
      keys, [&](const BoundaryKey& k) { return k.first == 0 ? name_in(names.faces, k.second) : nullptr; },
      [](const BoundaryKey& k) { return k.first == 0 ? "face_" + std::to_string(k.second) : std::string("defaultFaces"); });
  std::vector<std::string> order;
  for (const BoundaryKey& k : keys)
    if (std::find(order.begin(), order.end(), name.at(k)) == order.end()) order.push_back(name.at(k));
  for (const std::string& patch : order) {
    const Label start = static_cast<Label>(fc.faces.size());
    for (auto& [key, list] : boundary)
      if (name.at(key) == patch) fc.faces.insert(fc.faces.end(), list.begin(), list.end());
    fc.patches.push_back({patch, start, static_cast<Label>(fc.faces.size()) - start});
  }
}

// One cell zone per material ("material_<tag>") or per material name (the
// cells of all the regions of that name), in tag order; cells increasing.
void add_cell_zones(FoamCase& fc, const PolyMesh& m, const ModelNames& names) {
  std::set<std::int32_t> tags(m.cell_material.begin(), m.cell_material.end());
  const std::vector<std::int32_t> keys(tags.begin(), tags.end());
  const auto name = names_of(
      keys, [&](std::int32_t t) { return name_in(names.regions, t); },
      [](std::int32_t t) { return "material_" + std::to_string(t); });
  std::map<std::int32_t, std::size_t> zone_of;
  for (std::int32_t t : keys) {
    auto same = std::find_if(fc.cell_zones.begin(), fc.cell_zones.end(), [&](const auto& z) { return z.first == name.at(t); });
    if (same == fc.cell_zones.end()) same = fc.cell_zones.insert(same, {name.at(t), {}});
    zone_of[t] = static_cast<std::size_t>(same - fc.cell_zones.begin());
  }
  for (std::size_t c = 0; c < m.num_cells(); ++c)
    fc.cell_zones[zone_of.at(m.cell_material[c])].second.push_back(static_cast<Label>(c));
}

// The name of each interface and fracture face zone: its model face's name
// where it has one, else "interface_<tag>" / "fracture_<tag>".
std::map<std::pair<FaceKind, std::int32_t>, std::string> face_zone_names(const PolyMesh& m, const ModelNames& names) {
  std::set<std::pair<FaceKind, std::int32_t>> keys;
  for (std::size_t f = 0; f < m.num_faces(); ++f)
    if (m.face_kind[f] == FaceKind::Interface || m.face_kind[f] == FaceKind::Fracture)
      keys.insert({m.face_kind[f], m.face_tag[f]});
  return names_of(
      std::vector<std::pair<FaceKind, std::int32_t>>(keys.begin(), keys.end()),
      [&](const auto& k) { return name_in(names.faces, k.second); },
      [](const auto& k) { return (k.first == FaceKind::Interface ? "interface_" : "fracture_") + std::to_string(k.second); });
}

FoamCase build_case(const PolyMesh& m, const ModelNames& names, FoamReport& report) {
  FoamCase fc;
  std::vector<OutFace> internal;
  std::map<std::pair<int, std::int32_t>, std::vector<OutFace>> boundary;  // (0 tag | 1 default)
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    const CellId o = m.face_owner[f], n = m.face_neighbour[f];
    if (!o.valid() && !n.valid())
      throw InputError("<memory>", "face " + std::to_string(f), "belongs to no cell");
    OutFace out;
    out.source = FaceId(f);
    out.loop = without_spurs(m.face(FaceId(f)));
    if (out.loop.size() < 3) { ++report.dropped_degenerate_faces; continue; }
    if (out.loop.size() != m.face(FaceId(f)).size()) ++report.faces_without_spurs;
    if (o == n) {
      // A slit face: both sides bound the same cell, so it is written as a
      // baffle, two boundary faces of that cell (the loop, outward for the
      // PolyMesh side 0, and its reverse for side 1) in the patch of its model
      // face. Each of the cell's two half-faces then has its own face and the
      // cell is closed in OpenFOAM's sense.
      ++report.slit_faces;
      out.owner = o.idx;
      OutFace back = out;
      back.flipped = true;
      std::reverse(back.loop.begin(), back.loop.end());
      auto& patch = boundary[{0, m.face_tag[f]}];
      patch.push_back(std::move(out));
      patch.push_back(std::move(back));
    } else if (o.valid() && n.valid()) {
      out.flipped = o > n;
      out.owner = std::min(o, n).idx;
      out.neighbour = std::max(o, n).idx;
      if (out.flipped) std::reverse(out.loop.begin(), out.loop.end());
      internal.push_back(std::move(out));
    } else {
      out.flipped = !o.valid();
      out.owner = o.valid() ? o.idx : n.idx;
      const bool external = m.face_kind[f] == FaceKind::External;
      if (out.flipped) std::reverse(out.loop.begin(), out.loop.end());
      boundary[{external ? 0 : 1, external ? m.face_tag[f] : 0}].push_back(std::move(out));
    }
  }
  // Upper-triangular order; faces arrive in id order, so a stable sort breaks
  // ties (two faces between the same two cells) by PolyMesh face id.
  std::stable_sort(internal.begin(), internal.end(), [](const OutFace& a, const OutFace& b) {
    return std::tie(a.owner, a.neighbour) < std::tie(b.owner, b.neighbour);
  });
  fc.faces = std::move(internal);
  fc.internal = static_cast<Label>(fc.faces.size());
  add_patches(fc, boundary, names);

  // Keep only points that a kept face uses, in PolyMesh order.
  fc.point_map.assign(m.num_points(), -1);
  for (const OutFace& f : fc.faces)
    for (PointId p : f.loop) fc.point_map[p.idx] = 0;
  for (std::size_t p = 0; p < m.num_points(); ++p)
    if (fc.point_map[p] == 0) {
      fc.point_map[p] = static_cast<Label>(fc.points.size());
      fc.points.push_back(PointId(p));
    }

  add_cell_zones(fc, m, names);
  std::map<std::pair<FaceKind, std::int32_t>, FaceZone> zones;
  const auto zone_names = face_zone_names(m, names);
  for (std::size_t i = 0; i < fc.faces.size(); ++i) {
    const OutFace& f = fc.faces[i];
    const FaceKind kind = m.face_kind[f.source.idx];
    if (kind != FaceKind::Interface && kind != FaceKind::Fracture) continue;
    const std::int32_t tag = m.face_tag[f.source.idx];
    FaceZone& z = zones[{kind, tag}];
    z.name = zone_names.at({kind, tag});
    bool flip = f.flipped;  // keep the PolyMesh orientation...
    if (kind == FaceKind::Interface && f.neighbour >= 0) {  // ...or lower -> higher material
      const auto mo = m.cell_material[static_cast<std::size_t>(f.owner)];
      const auto mn = m.cell_material[static_cast<std::size_t>(f.neighbour)];
      if (mo != mn) flip = mo > mn;
    }
    z.faces.push_back(static_cast<Label>(i));
    z.flip.push_back(flip);
  }
  for (auto& entry : zones) {  // zones of one model name are one zone
    FaceZone& z = entry.second;  // not a structured binding: the lambda captures it
    auto same = std::find_if(fc.face_zones.begin(), fc.face_zones.end(), [&](const FaceZone& o) { return o.name == z.name; });
    if (same == fc.face_zones.end()) { fc.face_zones.push_back(std::move(z)); continue; }
    same->faces.insert(same->faces.end(), z.faces.begin(), z.faces.end());
    same->flip.insert(same->flip.end(), z.flip.begin(), z.flip.end());
  }

  report.points = fc.points.size();
  report.dropped_points = m.num_points() - fc.points.size();
  report.cells = m.num_cells();
  report.faces = fc.faces.size();
  report.internal_faces = static_cast<std::size_t>(fc.internal);
  report.patches = fc.patches.size();
  report.cell_zones = fc.cell_zones.size();
  report.face_zones = fc.face_zones.size();
  return fc;
}

// 17 significant digits: every double survives the decimal round trip exactly.
void put_real(std::ostream& os, double v) {
  std::array<char, 32> buf;
  auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::general, 17);
  os.write(buf.data(), r.ptr - buf.data());
}

void write_foam_file(const fs::path& file, const std::string& cls, const std::string& location,
                     const std::string& note, const std::function<void(std::ostream&)>& body) {
  write_file_atomically(file, [&](std::ostream& os) {
    os << "/*--------------------------------*- C++ -*----------------------------------*\\\n"
       << "  Written by polydual\n"
       << "\\*---------------------------------------------------------------------------*/\n"
       << "FoamFile\n{\n    version     2.0;\n    format      ascii;\n"
       << "    class       " << cls << ";\n";
    if (!note.empty()) os << "    note        \"" << note << "\";\n";
    os << "    location    \"" << location << "\";\n"
       << "    object      " << file.filename().string() << ";\n}\n"
       << "// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n\n";
    body(os);
    os << "\n// ************************************************************************* //\n";
  });
}

template <class T>
void put_inline_list(std::ostream& os, const char* type, const std::vector<T>& v) {
  os << "List<" << type << "> " << v.size() << "(";
  for (std::size_t i = 0; i < v.size(); ++i) os << (i ? " " : "") << static_cast<Label>(v[i]);
  os << ");\n";
}

void write_poly_mesh(const PolyMesh& m, const FoamCase& fc, const fs::path& dir,
                     const FoamOptions& opt) {
  const std::string loc = "constant/polyMesh";
  // checkMesh and the decomposition tools read these counts from the owner note.
  const std::string note = "nPoints:" + std::to_string(fc.points.size()) +
                           "  nCells:" + std::to_string(m.num_cells()) +
                           "  nFaces:" + std::to_string(fc.faces.size()) +
                           "  nInternalFaces:" + std::to_string(fc.internal);
  write_foam_file(dir / "points", "vectorField", loc, "", [&](std::ostream& os) {
    os << fc.points.size() << "\n(\n";
    for (PointId p : fc.points) {
      const Point3& x = m.points[p.idx];
      os << '(';
      put_real(os, x.x); os << ' ';
      put_real(os, x.y); os << ' ';
      put_real(os, x.z); os << ")\n";
    }
    os << ")\n";
  });
  write_foam_file(dir / "faces", "faceList", loc, "", [&](std::ostream& os) {
    os << fc.faces.size() << "\n(\n";
    for (const OutFace& f : fc.faces) {
      os << f.loop.size() << '(';
      for (std::size_t k = 0; k < f.loop.size(); ++k)
        os << (k ? " " : "") << fc.point_map[f.loop[k].idx];
      os << ")\n";
    }
    os << ")\n";
  });
  write_foam_file(dir / "owner", "labelList", loc, note, [&](std::ostream& os) {
    os << fc.faces.size() << "\n(\n";
    for (const OutFace& f : fc.faces) os << f.owner << '\n';
    os << ")\n";
  });
  write_foam_file(dir / "neighbour", "labelList", loc, note, [&](std::ostream& os) {
    os << fc.internal << "\n(\n";
    for (Label i = 0; i < fc.internal; ++i) os << fc.faces[static_cast<std::size_t>(i)].neighbour << '\n';
    os << ")\n";
  });
  write_foam_file(dir / "boundary", "polyBoundaryMesh", loc, "", [&](std::ostream& os) {
    os << fc.patches.size() << "\n(\n";
    for (const Patch& p : fc.patches)
      os << "    " << p.name << "\n    {\n        type            "
         << (p.name == "defaultFaces" ? "patch" : opt.patch_type) << ";\n"
         << "        nFaces          " << p.size << ";\n        startFace       " << p.start
         << ";\n    }\n";
    os << ")\n";
  });
  write_foam_file(dir / "cellZones", "regIOobject", loc, "", [&](std::ostream& os) {
    os << fc.cell_zones.size() << "\n(\n";
    for (const auto& [name, cells] : fc.cell_zones) {
      os << name << "\n{\n    type cellZone;\ncellLabels      ";
      put_inline_list(os, "label", cells);
      os << "}\n";
    }
    os << ")\n";
  });
  write_foam_file(dir / "faceZones", "regIOobject", loc, "", [&](std::ostream& os) {
    os << fc.face_zones.size() << "\n(\n";
    for (const FaceZone& z : fc.face_zones) {
      os << z.name << "\n{\n    type faceZone;\nfaceLabels      ";
      put_inline_list(os, "label", z.faces);
      os << "flipMap         ";
      put_inline_list(os, "bool", z.flip);
      os << "}\n";
    }
    os << ")\n";
  });
}

// The smallest system/ that lets OpenFOAM utilities open the case.
void write_system(const fs::path& dir) {
  write_foam_file(dir / "controlDict", "dictionary", "system", "", [](std::ostream& os) {
    os << "application     polydual;\nstartFrom       startTime;\nstartTime       0;\n"
          "stopAt          endTime;\nendTime         1;\ndeltaT          1;\n"
          "writeControl    timeStep;\nwriteInterval   1;\nwriteFormat     ascii;\n"
          "writePrecision  17;\n";
  });
  write_foam_file(dir / "fvSchemes", "dictionary", "system", "", [](std::ostream& os) {
    os << "ddtSchemes { default steadyState; }\ngradSchemes { default Gauss linear; }\n"
          "divSchemes { default none; }\nlaplacianSchemes { default Gauss linear corrected; }\n"
          "interpolationSchemes { default linear; }\nsnGradSchemes { default corrected; }\n";
  });
  write_foam_file(dir / "fvSolution", "dictionary", "system", "", [](std::ostream& os) {
    os << "solvers { }\n";
  });
}

}  // namespace

namespace {

// Creates `dir` and its missing ancestors; returns the ones it created,
// outermost first, so a failed write can remove them again.
std::vector<fs::path> create_missing_directories(const fs::path& dir) {
  std::vector<fs::path> missing;
  for (fs::path p = dir; !p.empty() && !fs::exists(fs::symlink_status(p)); p = p.parent_path())
    missing.push_back(p);
  std::vector<fs::path> created;
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    std::error_code ec;
    if (fs::create_directory(*it, ec)) created.push_back(*it);
    else if (ec) {
      for (auto c = created.rbegin(); c != created.rend(); ++c) fs::remove(*c, ec);
      throw WriteError(*it, "cannot create directory", ec);
    }
  }
  return created;
}

}  // namespace

FoamReport write_foam(const PolyMesh& mesh, const std::string& case_dir, const FoamOptions& options,
                      const ModelNames& names) {
  if (options.patch_type.empty() || options.patch_type.find_first_of(" ;{}\"") != std::string::npos)
    throw UsageError("write_foam: bad patch type '" + options.patch_type + "'");
  check_case_directory(case_dir, options.force);
  throw_if_interrupted();
  FoamReport report;
  const FoamCase fc = build_case(mesh, names, report);
  const fs::path dir(case_dir), poly = dir / "constant" / "polyMesh";
  const bool had_mesh = fs::exists(fs::symlink_status(poly));
  const std::vector<fs::path> created = create_missing_directories(dir / "constant");
  std::vector<std::unique_ptr<ScopedTemporary>> registered;  // removed if the watchdog ends the run
  for (const fs::path& c : created)
    registered.push_back(std::make_unique<ScopedTemporary>(c, ScopedTemporary::Kind::EmptyDir));
  try {
    write_directory_atomically(poly, [&](const fs::path& tmp) { write_poly_mesh(mesh, fc, tmp, options); });
    if (options.write_system) write_directory_if_absent(dir / "system", write_system);
  } catch (...) {
    // A case that did not exist is not left half made; an old polyMesh was
    // either kept or replaced by the complete new one.
    std::error_code ec;
    if (!had_mesh) fs::remove_all(poly, ec);
    for (auto c = created.rbegin(); c != created.rend(); ++c) fs::remove(*c, ec);  // empty ones only
    throw;
  }
  return report;
}

}  // namespace polydual
