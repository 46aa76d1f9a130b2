// The VTK XML layer shared by the .vtu readers (vtu_reader: tets, vtu_poly_reader:
// polyhedra): the element tree of a VTKFile and the decoding of its DataArrays.
//
// What VTK and meshio write is understood:
//   - XML: declaration, comments, start/end/empty tags with quoted attributes,
//     character data (the values of ascii/binary DataArrays);
//   - <VTKFile byte_order="LittleEndian" header_type="UInt32|UInt64"
//     compressor="vtkZLibDataCompressor"?> (header_type defaults to UInt32);
//   - DataArray format="ascii" (decimal text), "binary" (base64 inline) and
//     "appended" (offset="N" into <AppendedData encoding="raw"|"base64">, after
//     its '_' marker);
//   - types Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float32,
//     Float64 (VTK 9 and meshio write only these names);
//   - binary payloads: [byte count][bytes] uncompressed, or with the zlib
//     compressor [block count][block size][last block size][compressed size per
//     block][zlib blocks], every header word of header_type.
//
// Every failure is an InputError naming the source and the place: "line N" of
// the element for XML and inline data, "byte N" (absolute file offset) inside
// appended data, with the DataArray's Name. Sizes read from the file are
// checked against the bytes present before anything is allocated by them (a
// zlib block may claim at most kMaxZlibRatio times its compressed size), so
// malformed or truncated input is an error, never a crash or a huge allocation.
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace polydual::io {
class InputFile;
}

namespace polydual::io::vtkxml {

// All of a VTK XML file, refused as soon as it cannot be one, before the
// rest is read: no NUL byte may come before <AppendedData> (only raw appended
// data is binary; a zero-filled file fails in its first 64 KiB), and the last
// non-blank byte must be the '>' of a tag (a file cut short or padded with
// zeros fails from its last bytes alone). Errors name the line or byte.
std::string_view load_vtk_xml(InputFile& file);

// One element of the document (the scanner keeps them all, in file order).
struct Element {
  std::string_view name;
  std::vector<std::pair<std::string_view, std::string_view>> attrs;
  std::size_t begin = 0;   // byte offset of its '<'
  std::string_view text;   // character data before the first child or the end tag
  std::size_t text_pos = 0;  // byte offset of `text`
  int parent = -1;         // index into VtkXml::elements(), -1 for the root
  std::optional<std::string_view> attr(std::string_view key) const {
    for (const auto& [k, v] : attrs)
      if (k == key) return v;
    return std::nullopt;
  }
};

enum class Scalar : std::uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float32, Float64 };
std::size_t scalar_bytes(Scalar s);
bool scalar_is_integer(Scalar s);
std::string_view scalar_name(Scalar s);

// zlib cannot expand data by more than about 1032:1; a block header claiming
// more is corrupt (and would otherwise size an allocation).
inline constexpr std::uint64_t kMaxZlibRatio = 1100;

class VtkXml {
 public:
  // Scans `bytes` (kept by view: they must outlive this object) and checks the
  // <VTKFile>: its type must be `grid_type` ("UnstructuredGrid"), little
  // endian, a known header_type and compressor.
  VtkXml(std::string_view bytes, std::string source, std::string_view grid_type);

  const std::vector<Element>& elements() const { return elements_; }
  const std::string& source() const { return source_; }
  // The one <Piece>; "no <Piece>" / "more than one Piece not supported".
  const Element& piece() const;
  // The name of the element's parent ("" for the root).
  std::string_view parent_name(const Element& e) const {
    return e.parent < 0 ? std::string_view() : elements_[e.parent].name;
  }
  // The first DataArray directly inside an element named `section` (e.g.
  // "Points", "Cells", "CellData", "FieldData") whose Name is `name`; with an
  // empty `name`, the first DataArray there whatever its name. nullptr if none.
  const Element* find_array(std::string_view section, std::string_view name = {}) const;

  // A non-negative integer attribute that counts items of the file (points,
  // cells): at most the file's size, since each takes at least a byte.
  std::int64_t count_attr(const Element& e, std::string_view key) const;

  // DataArray facts. name(): its Name or "(unnamed)".
  std::string array_name(const Element& a) const;
  Scalar array_type(const Element& a) const;
  std::int64_t components(const Element& a) const;  // NumberOfComponents, 1 when absent
  // Its values converted, whatever its format: integers() needs an integer type
  // (UInt64 above 2^63-1 is an error), reals() takes any type and rejects
  // non-finite values. The count is a multiple of components().
  std::vector<std::int64_t> integers(const Element& a) const;
  std::vector<double> reals(const Element& a) const;
  // integers() with every value in [lo, hi], else "DataArray 'x': value v at
  // index i out of range (lo..hi)".
  std::vector<std::int64_t> integers_in(const Element& a, std::int64_t lo, std::int64_t hi) const;

  std::size_t line_at(std::size_t pos) const;
  [[noreturn]] void fail(std::size_t pos, const std::string& what) const;          // "line N"
  [[noreturn]] void fail_byte(std::size_t pos, const std::string& what) const;     // "byte N"
  [[noreturn]] void fail_at(const std::string& place, const std::string& what) const;

 private:
  void scan();
  std::size_t scan_tag(std::size_t lt, std::vector<int>& stack);
  void scan_appended(const Element& e, std::size_t after_tag);
  void check_root();

  // The little-endian payload of a binary or appended array: a view of the
  // file (raw appended, uncompressed) or of `storage` (decoded or inflated).
  std::string_view payload(const Element& a, std::string& storage) const;
  std::string_view inline_payload(const Element& a, std::string& storage) const;
  std::string_view appended_payload(const Element& a, std::string& storage) const;
  template <class T>
  void convert(const Element& a, std::vector<T>& out) const;
  template <class T>
  void parse_ascii(const Element& a, std::vector<T>& out) const;

  std::string_view bytes_;
  std::string source_;
  std::vector<Element> elements_;
  bool header64_ = false, zlib_ = false;
  // <AppendedData>: its encoding and the bytes after '_' up to </AppendedData>.
  bool appended_base64_ = false;
  std::optional<std::pair<std::size_t, std::size_t>> appended_;  // [begin, end)
};

// base64 (RFC 4648, whitespace ignored) read on demand, so that an appended
// array is decoded from its offset without decoding the rest. Concatenated
// padded streams (VTK encodes a header and its data separately) read as one.
class Base64Reader {
 public:
  explicit Base64Reader(std::string_view text) : text_(text) {}
  // Appends up to n decoded bytes to out; returns how many (fewer at the end
  // of the text). nullopt on a character outside the alphabet or bad padding.
  std::optional<std::size_t> read(std::size_t n, std::string& out);
  // An upper bound of the bytes still decodable.
  std::size_t max_remaining() const {
    return (text_.size() - pos_) / 4 * 3 + static_cast<std::size_t>(carry_n_ - carry_at_);
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  unsigned char carry_[3] = {0, 0, 0};
  int carry_n_ = 0, carry_at_ = 0;
};

// base64 text of `bytes` (with padding), as VTK writes it.
std::string encode_base64(std::string_view bytes);

// VTK's zlib payload of `data`: the header of header words (block count,
// block size, last block size, compressed sizes) then the zlib blocks of
// `block_size` bytes at `level` (1..9). `header64`: UInt64 words, else UInt32.
struct ZlibPayload {
  std::string header, blocks;
};
ZlibPayload zlib_compress(std::string_view data, int level, bool header64, std::size_t block_size = 32768);

}  // namespace polydual::io::vtkxml
