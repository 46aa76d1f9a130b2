#include "io/vtu_poly_writer.h"

#include <array>
#include <bit>
#include <charconv>
#include <cstring>
#include <functional>
#include <limits>
#include <optional>
#include <ostream>
#include <map>
#include <set>
#include <type_traits>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/vtk_xml.h"

namespace polydual {
namespace {

// Binary arrays are the in-memory bytes; the file declares LittleEndian.
static_assert(std::endian::native == std::endian::little, "vtu binary mode assumes little endian");

constexpr std::uint8_t kVtkPolyhedron = 42;

// One number as text. Doubles get 17 significant digits: that is the smallest
// count that makes every IEEE binary64 value round-trip through decimal exactly,
// so the reader recovers bit-identical coordinates (the validity test is exact,
// a rounded point could flip a cell's verdict). to_chars is locale-independent.
template <class T>
void put_number(std::string& s, T v) {
  std::array<char, 32> buf;
  std::to_chars_result r;
  if constexpr (std::is_floating_point_v<T>)
    r = std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::general, 17);
  else
    r = std::to_chars(buf.data(), buf.data() + buf.size(), static_cast<std::int64_t>(v));
  s.append(buf.data(), r.ptr);
}

// Receives an array's values in file order. With a stream (appended raw
// output) the bytes go to it through a fixed buffer, so no array is ever held
// whole; without one they are collected for encoding (base64, zlib, ascii),
// one array at a time.
class ByteSink {
 public:
  // `capacity`: the bytes to collect, when known (no stream).
  explicit ByteSink(std::ostream* os, std::size_t capacity = 0) : os_(os) {
    buf_.reserve(os_ ? kChunk : capacity);
  }
  template <class T>
  void put(T v) {
    append(&v, sizeof v);
  }
  void append(const void* p, std::size_t n) {
    if (os_ && buf_.size() + n > kChunk) {
      flush();
      if (n >= kChunk) {  // a whole vector: straight to the stream
        os_->write(static_cast<const char*>(p), static_cast<std::streamsize>(n));
        return;
      }
    }
    buf_.append(static_cast<const char*>(p), n);
  }
  void flush() {
    if (!os_) return;
    os_->write(buf_.data(), static_cast<std::streamsize>(buf_.size()));
    buf_.clear();
  }
  std::string take() { return std::move(buf_); }

 private:
  // As core/atomic_file.cpp's chunk: a full buffer passes through the file's
  // stream buffer without a copy.
  static constexpr std::size_t kChunk = std::size_t{256} << 10;
  std::ostream* os_;
  std::string buf_;
};

// One DataArray to write: its XML attributes, its size, the producer of its
// values (called once per output pass) and their ascii form.
struct OutArray {
  const char* type;
  std::string name;
  int components;
  bool field_data;     // FieldData arrays declare NumberOfTuples
  std::size_t count;   // values
  std::size_t nbytes;  // count * value size
  std::function<void(ByteSink&)> produce;
  std::function<void(std::ostream&, std::string_view)> ascii;  // from the bytes
};

template <class T>
OutArray out_array(const char* type, std::string name, int components, std::size_t count,
                   std::function<void(ByteSink&)> produce, bool field_data = false) {
  OutArray a{type, std::move(name), components, field_data, count, count * sizeof(T), std::move(produce), {}};
  a.ascii = [components](std::ostream& os, std::string_view bytes) {
    const std::size_t n = bytes.size() / sizeof(T);
    const std::size_t per_line = components > 1 ? static_cast<std::size_t>(components) : 12;
    std::string line;
    for (std::size_t i = 0; i < n; ++i) {
      T v;
      std::memcpy(&v, bytes.data() + i * sizeof(T), sizeof(T));
      if (i % per_line == 0) line = "          ";
      else line += ' ';
      put_number(line, v);
      if (i % per_line == per_line - 1 || i + 1 == n) os << line << "\n";
    }
  };
  return a;
}

// An array that is already a vector in memory.
template <class T>
OutArray vector_array(const char* type, std::string name, const std::vector<T>& v) {
  return out_array<T>(type, std::move(name), 1, v.size(),
                      [&v](ByteSink& s) { s.append(v.data(), v.size() * sizeof(T)); });
}

// The values of an array, whole (the encodings that need them at once),
// after `prefix`, in one allocation.
std::string bytes_of(const OutArray& a, std::string_view prefix = {}) {
  ByteSink sink(nullptr, prefix.size() + a.nbytes);
  sink.append(prefix.data(), prefix.size());
  a.produce(sink);
  return sink.take();
}

// The UInt64 byte count that precedes an uncompressed binary array.
std::string size_header(std::uint64_t n) { return std::string(reinterpret_cast<const char*>(&n), sizeof n); }

void write_array(std::ostream& os, const OutArray& a, const VtuOptions& o, std::optional<std::uint64_t> offset) {
  os << "        <DataArray type=\"" << a.type << "\" Name=\"" << a.name << "\"";
  if (a.components > 1) os << " NumberOfComponents=\"" << a.components << "\"";
  if (a.field_data) os << " NumberOfTuples=\"" << a.count << "\"";
  if (offset) {
    os << " format=\"appended\" offset=\"" << *offset << "\"/>\n";
    return;
  }
  os << " format=\"" << (o.binary ? "binary" : "ascii") << "\">\n";
  if (!o.binary) {
    a.ascii(os, bytes_of(a));
  } else if (o.zlib_level > 0) {
    // As VTK does: the header and the blocks as two base64 streams.
    const io::vtkxml::ZlibPayload z = io::vtkxml::zlib_compress(bytes_of(a), o.zlib_level, true);
    os << "          " << io::vtkxml::encode_base64(z.header) << io::vtkxml::encode_base64(z.blocks) << "\n";
  } else {
    // The byte count and the values base64-encoded together as one stream.
    const std::string raw = bytes_of(a, size_header(a.nbytes));
    os << "          " << io::vtkxml::encode_base64(raw) << "\n";
  }
  os << "        </DataArray>\n";
}

// The arrays of the file by section, each section in file order.
struct Layout {
  std::vector<OutArray> field, point, cell, points, cells;
  std::vector<const OutArray*> in_file_order() const {
    std::vector<const OutArray*> all;
    for (const auto* section : {&field, &point, &cell, &points, &cells})
      for (const OutArray& a : *section) all.push_back(&a);
    return all;
  }
};

// The XML part of the file; with `offsets` (one per array in file order) the
// arrays are appended at those offsets.
void write_xml(std::ostream& os, std::size_t np, std::size_t nc, const Layout& layout, const VtuOptions& o,
               const std::vector<std::uint64_t>* offsets) {
  std::size_t i = 0;
  auto section = [&](const char* open, const char* close, const std::vector<OutArray>& arrays) {
    os << open;
    for (const OutArray& a : arrays)
      write_array(os, a, o, offsets ? std::optional<std::uint64_t>((*offsets)[i++]) : std::nullopt);
    os << close;
  };
  os << "<?xml version=\"1.0\"?>\n"
     << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\""
     << " header_type=\"UInt64\"" << (o.zlib_level > 0 ? " compressor=\"vtkZLibDataCompressor\"" : "")
     << ">\n  <UnstructuredGrid>\n";
  section("    <FieldData>\n", "    </FieldData>\n", layout.field);
  os << "    <Piece NumberOfPoints=\"" << np << "\" NumberOfCells=\"" << nc << "\">\n";
  section("      <PointData>\n", "      </PointData>\n", layout.point);
  section("      <CellData>\n", "      </CellData>\n", layout.cell);
  section("      <Points>\n", "      </Points>\n", layout.points);
  section("      <Cells>\n", "      </Cells>\n", layout.cells);
  os << "    </Piece>\n  </UnstructuredGrid>\n";
}

// Appended output: the XML with every array's offset, then '_' and the
// payloads. Uncompressed payloads are streamed from their producers (their
// sizes are known up front); compressed ones must be compressed first, since
// the offsets depend on their sizes, and only they are kept.
void write_appended(std::ostream& os, std::size_t np, std::size_t nc, const Layout& layout, const VtuOptions& o) {
  const std::vector<const OutArray*> arrays = layout.in_file_order();
  std::vector<io::vtkxml::ZlibPayload> zipped;
  std::vector<std::uint64_t> offsets;
  std::uint64_t at = 0;
  for (const OutArray* a : arrays) {
    offsets.push_back(at);
    if (o.zlib_level > 0) {
      zipped.push_back(io::vtkxml::zlib_compress(bytes_of(*a), o.zlib_level, true));
      at += zipped.back().header.size() + zipped.back().blocks.size();
    } else {
      at += sizeof(std::uint64_t) + a->nbytes;
    }
  }
  write_xml(os, np, nc, layout, o, &offsets);
  os << "  <AppendedData encoding=\"raw\">\n   _";
  ByteSink sink(&os);
  for (std::size_t i = 0; i < arrays.size(); ++i) {
    if (o.zlib_level > 0) {
      sink.append(zipped[i].header.data(), zipped[i].header.size());
      sink.append(zipped[i].blocks.data(), zipped[i].blocks.size());
    } else {
      sink.put(static_cast<std::uint64_t>(arrays[i]->nbytes));
      arrays[i]->produce(sink);
    }
  }
  sink.flush();
  os << "\n  </AppendedData>\n</VTKFile>\n";
}

// The whole file.
void write_file(std::ostream& os, std::size_t np, std::size_t nc, const Layout& layout, const VtuOptions& o) {
  if (o.appended) return write_appended(os, np, nc, layout, o);
  write_xml(os, np, nc, layout, o, nullptr);
  os << "</VTKFile>\n";
}

void check_options(const PolyMesh& mesh, const std::vector<CellField>& extra, const VtuOptions& options) {
  if (options.zlib_level < 0 || options.zlib_level > 9)
    throw UsageError("write_vtu_poly: zlib level " + std::to_string(options.zlib_level) + " outside 0..9");
  if (options.zlib_level > 0 && !options.binary && !options.appended)
    throw UsageError("write_vtu_poly: zlib compression needs binary or appended output");
  const std::size_t nc = mesh.num_cells();
  std::set<std::string> names{"material", "primal_vertex"};
  for (const CellField& f : extra) {
    const std::size_t n = std::visit([](const auto& v) { return v.size(); }, f.values);
    if (n != nc)
      throw UsageError("write_vtu_poly: field '" + f.name + "' has " + std::to_string(n) +
                       " values for " + std::to_string(nc) + " cells");
    if (f.name.empty() || f.name.find_first_of("\"<>&") != std::string::npos ||
        !names.insert(f.name).second)
      throw UsageError("write_vtu_poly: bad or duplicate cell field name '" + f.name + "'");
  }
}

// Per cell, the end of its distinct points in `connectivity` and of its
// record in `faces` (the VTK offsets arrays), and the number of faces.
struct CellOffsets {
  std::vector<std::int64_t> points, faces;
  std::size_t half_faces = 0;
};
CellOffsets cell_offsets(const PolyMesh& mesh) {
  CellOffsets o;
  const std::size_t nc = mesh.num_cells();
  o.points.resize(nc);
  o.faces.resize(nc);
  std::int64_t np = 0, nf = 0;
  CellPointScan points(mesh);
  for (std::size_t c = 0; c < nc; ++c) {
    const CellId cell(c);
    np += static_cast<std::int64_t>(points(cell).size());
    nf += 1;
    for (HalfFace h : mesh.cell(cell)) nf += 1 + static_cast<std::int64_t>(mesh.face(h.face()).size());
    o.half_faces += mesh.cell(cell).size();
    o.points[c] = np;
    o.faces[c] = nf;
  }
  return o;
}

// The Cells section: connectivity (distinct points, first-seen order),
// offsets, types, faces (per cell: nFaces, then nPts ids... in the cell's
// outward orientation), faceoffsets; every index of type I (named itype).
template <class I>
std::vector<OutArray> cell_arrays_of(const PolyMesh& mesh, const CellOffsets& off, const char* itype) {
  const std::size_t nc = mesh.num_cells();
  const std::size_t nconn = nc ? static_cast<std::size_t>(off.points.back()) : 0;
  const std::size_t nfaces = nc ? static_cast<std::size_t>(off.faces.back()) : 0;
  auto connectivity = [&mesh, nc](ByteSink& s) {
    CellPointScan points(mesh);
    for (std::size_t c = 0; c < nc; ++c)
      for (PointId p : points(CellId(c))) s.put(static_cast<I>(p.idx));
  };
  auto faces = [&mesh, nc](ByteSink& s) {
    for (std::size_t c = 0; c < nc; ++c) {
      const auto cell = mesh.cell(CellId(c));
      s.put(static_cast<I>(cell.size()));
      for (HalfFace h : cell) {
        const auto f = mesh.face(h.face());
        s.put(static_cast<I>(f.size()));
        if (h.side() == 1)
          for (std::size_t i = f.size(); i-- > 0;) s.put(static_cast<I>(f[i].idx));
        else
          for (PointId p : f) s.put(static_cast<I>(p.idx));
      }
    }
  };
  auto offsets = [](const std::vector<std::int64_t>& v) {
    return [&v](ByteSink& s) {
      for (std::int64_t x : v) s.put(static_cast<I>(x));
    };
  };
  auto types = [nc](ByteSink& s) {
    for (std::size_t c = 0; c < nc; ++c) s.put(kVtkPolyhedron);
  };
  return {out_array<I>(itype, "connectivity", 1, nconn, connectivity),
          out_array<I>(itype, "offsets", 1, nc, offsets(off.points)),
          out_array<std::uint8_t>("UInt8", "types", 1, nc, types), out_array<I>(itype, "faces", 1, nfaces, faces),
          out_array<I>(itype, "faceoffsets", 1, nc, offsets(off.faces))};
}

// Int32 indices when every one fits (half the bytes of the Cells section,
// which is most of the file), else Int64. VTK reads either (it converts
// connectivity, offsets, faces and faceoffsets to vtkIdType), and so does
// io/vtu_poly_reader.
std::vector<OutArray> cell_arrays(const PolyMesh& mesh, const CellOffsets& off) {
  constexpr std::int64_t kMax = std::numeric_limits<std::int32_t>::max();
  const bool fits = static_cast<std::int64_t>(mesh.num_points()) <= kMax &&
                    (off.points.empty() || (off.points.back() <= kMax && off.faces.back() <= kMax));
  return fits ? cell_arrays_of<std::int32_t>(mesh, off, "Int32") : cell_arrays_of<std::int64_t>(mesh, off, "Int64");
}

// Every array but the Cells section, built from the mesh as it is written.
// The names of `named` as FieldData: `tag_name` (Int32, the tags) and
// `name` (a VTK String array: each name's bytes and a 0, one tuple each).
void add_name_arrays(std::vector<OutArray>& field, const std::map<std::int32_t, std::string>& named,
                     const char* tag_name, const char* name) {
  if (named.empty()) return;
  field.push_back(out_array<std::int32_t>("Int32", tag_name, 1, named.size(), [&named](ByteSink& s) {
    for (const auto& [tag, n] : named) s.put(tag);
  }, true));
  std::size_t nbytes = 0;
  for (const auto& [tag, n] : named) nbytes += n.size() + 1;
  OutArray a = out_array<std::uint8_t>("String", name, 1, nbytes, [&named](ByteSink& s) {
    for (const auto& [tag, n] : named) s.append(n.c_str(), n.size() + 1);
  }, true);
  a.count = named.size();  // NumberOfTuples: strings, not bytes
  field.push_back(std::move(a));
}

Layout layout_of(const PolyMesh& mesh, const std::vector<CellField>& extra, const CellOffsets& off,
                 const ModelNames& names) {
  const std::size_t nc = mesh.num_cells(), np = mesh.num_points();
  auto per_half_face = [&mesh, nc](bool kind) {
    return [&mesh, nc, kind](ByteSink& s) {
      for (std::size_t c = 0; c < nc; ++c)
        for (HalfFace h : mesh.cell(CellId(c)))
          s.put(kind ? static_cast<std::int32_t>(mesh.face_kind[h.face().idx])
                      : static_cast<std::int32_t>(mesh.face_tag[h.face().idx]));
    };
  };
  Layout l;
  l.field = {out_array<std::int32_t>("Int32", "face_kind", 1, off.half_faces, per_half_face(true), true),
             out_array<std::int32_t>("Int32", "face_tag", 1, off.half_faces, per_half_face(false), true)};
  add_name_arrays(l.field, names.regions, "region_name_tag", "region_name");
  add_name_arrays(l.field, names.faces, "face_name_tag", "face_name");
  l.point = {out_array<std::int8_t>("Int8", "class_dim", 1, np,
                                    [&mesh, np](ByteSink& s) {
                                      for (std::size_t i = 0; i < np; ++i) s.put(static_cast<std::int8_t>(mesh.point_class[i].dim));
                                    }),
             out_array<std::int32_t>("Int32", "class_tag", 1, np, [&mesh, np](ByteSink& s) {
               for (std::size_t i = 0; i < np; ++i) s.put(static_cast<std::int32_t>(mesh.point_class[i].tag));
             })};
  l.cell = {vector_array("Int32", "material", mesh.cell_material),
            out_array<std::int64_t>("Int64", "primal_vertex", 1, nc, [&mesh, nc](ByteSink& s) {
              for (std::size_t c = 0; c < nc; ++c)
                s.put(mesh.cell_primal[c].valid() ? static_cast<std::int64_t>(mesh.cell_primal[c].idx) : -1);
            })};
  for (const CellField& f : extra) {
    if (const auto* d = std::get_if<std::vector<double>>(&f.values)) l.cell.push_back(vector_array("Float64", f.name, *d));
    else l.cell.push_back(vector_array("Int32", f.name, std::get<std::vector<std::int32_t>>(f.values)));
  }
  l.points = {out_array<double>("Float64", "Points", 3, 3 * np, [&mesh, np](ByteSink& s) {
    for (std::size_t i = 0; i < np; ++i) {
      const double xyz[3] = {mesh.points[i].x, mesh.points[i].y, mesh.points[i].z};
      s.append(xyz, sizeof xyz);
    }
  })};
  l.cells = cell_arrays(mesh, off);
  return l;
}

}  // namespace

void write_vtu_poly(const PolyMesh& mesh, const std::string& path, const std::vector<CellField>& extra,
                    const VtuOptions& options, const ModelNames& names) {
  check_options(mesh, extra, options);
  const CellOffsets offsets = cell_offsets(mesh);
  const Layout l = layout_of(mesh, extra, offsets, names);
  write_file_atomically(path, [&](std::ostream& os) { write_file(os, mesh.num_points(), mesh.num_cells(), l, options); },
                        options.binary || options.appended);
}

}  // namespace polydual
