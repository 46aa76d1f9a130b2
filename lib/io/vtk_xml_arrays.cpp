// DataArray decoding of the VTK XML layer (lib/io/vtk_xml.h): ascii text,
// base64, appended raw/base64 data, zlib-compressed blocks, and the conversion
// of the ten VTK scalar types to int64 / double with range checks.
#include <zlib.h>

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

#include "core/error.h"
#include "io/text_cursor.h"
#include "io/vtk_xml.h"

namespace polydual::io::vtkxml {
namespace {

static_assert(std::endian::native == std::endian::little, "VTK binary data is read as little endian");

struct ScalarInfo {
  std::string_view name;
  std::size_t bytes;
  bool integer;
};
constexpr std::array<ScalarInfo, 10> kScalars{{{"Int8", 1, true},
                                               {"UInt8", 1, true},
                                               {"Int16", 2, true},
                                               {"UInt16", 2, true},
                                               {"Int32", 4, true},
                                               {"UInt32", 4, true},
                                               {"Int64", 8, true},
                                               {"UInt64", 8, true},
                                               {"Float32", 4, false},
                                               {"Float64", 8, false}}};

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

constexpr std::array<signed char, 256> kBase64Value = [] {
  std::array<signed char, 256> t{};
  t.fill(-1);
  for (int i = 0; i < 26; ++i) t['A' + i] = static_cast<signed char>(i), t['a' + i] = static_cast<signed char>(26 + i);
  for (int i = 0; i < 10; ++i) t['0' + i] = static_cast<signed char>(52 + i);
  t['+'] = 62;
  t['/'] = 63;
  return t;
}();

// Visits the value of scalar type `s` at `p` as its C++ type.
template <class F>
void with_scalar(Scalar s, F&& f) {
  switch (s) {
    case Scalar::Int8: return f(std::int8_t{});
    case Scalar::UInt8: return f(std::uint8_t{});
    case Scalar::Int16: return f(std::int16_t{});
    case Scalar::UInt16: return f(std::uint16_t{});
    case Scalar::Int32: return f(std::int32_t{});
    case Scalar::UInt32: return f(std::uint32_t{});
    case Scalar::Int64: return f(std::int64_t{});
    case Scalar::UInt64: return f(std::uint64_t{});
    case Scalar::Float32: return f(float{});
    case Scalar::Float64: return f(double{});
  }
}

}  // namespace

std::size_t scalar_bytes(Scalar s) { return kScalars[static_cast<int>(s)].bytes; }
bool scalar_is_integer(Scalar s) { return kScalars[static_cast<int>(s)].integer; }
std::string_view scalar_name(Scalar s) { return kScalars[static_cast<int>(s)].name; }

// ---- base64 ---------------------------------------------------------------

std::optional<std::size_t> Base64Reader::read(std::size_t n, std::string& out) {
  std::size_t done = 0;
  while (done < n) {
    if (carry_at_ < carry_n_) {
      out += static_cast<char>(carry_[carry_at_++]);
      ++done;
      continue;
    }
    int v[4], got = 0, pad = 0;
    while (got < 4 && pos_ < text_.size()) {
      const char c = text_[pos_++];
      if (is_space(c)) continue;
      if (c == '=' && got >= 2) { v[got++] = 0; ++pad; continue; }
      if (pad > 0) return std::nullopt;  // data after '=' inside a group
      v[got] = kBase64Value[static_cast<unsigned char>(c)];
      if (v[got++] < 0) return std::nullopt;
    }
    if (got == 0) break;
    if (got < 4) return std::nullopt;  // a truncated group
    const std::uint32_t bits = (std::uint32_t(v[0]) << 18) | (std::uint32_t(v[1]) << 12) |
                               (std::uint32_t(v[2]) << 6) | std::uint32_t(v[3]);
    carry_[0] = static_cast<unsigned char>(bits >> 16);
    carry_[1] = static_cast<unsigned char>(bits >> 8);
    carry_[2] = static_cast<unsigned char>(bits);
    carry_n_ = 3 - pad;
    carry_at_ = 0;
  }
  return done;
}

std::string encode_base64(std::string_view in) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < in.size(); i += 3) {
    const std::uint32_t b0 = static_cast<unsigned char>(in[i]);
    const std::uint32_t b1 = i + 1 < in.size() ? static_cast<unsigned char>(in[i + 1]) : 0;
    const std::uint32_t b2 = i + 2 < in.size() ? static_cast<unsigned char>(in[i + 2]) : 0;
    const std::uint32_t n = (b0 << 16) | (b1 << 8) | b2;
    const char quad[4] = {kAlphabet[(n >> 18) & 63], kAlphabet[(n >> 12) & 63],
                          i + 1 < in.size() ? kAlphabet[(n >> 6) & 63] : '=', i + 2 < in.size() ? kAlphabet[n & 63] : '='};
    out.append(quad, 4);
  }
  return out;
}

// ---- zlib -------------------------------------------------------------------

ZlibPayload zlib_compress(std::string_view data, int level, bool header64, std::size_t block_size) {
  const std::size_t nblocks = (data.size() + block_size - 1) / block_size;
  std::vector<std::uint64_t> words{nblocks, block_size, nblocks ? data.size() - (nblocks - 1) * block_size : 0};
  ZlibPayload out;
  for (std::size_t b = 0; b < nblocks; ++b) {
    const std::string_view block = data.substr(b * block_size, block_size);
    uLongf size = compressBound(static_cast<uLong>(block.size()));
    const std::size_t at = out.blocks.size();
    out.blocks.resize(at + size);
    if (compress2(reinterpret_cast<Bytef*>(out.blocks.data() + at), &size, reinterpret_cast<const Bytef*>(block.data()),
                  static_cast<uLong>(block.size()), level) != Z_OK)
      throw std::runtime_error("zlib compress2 failed");
    out.blocks.resize(at + size);
    words.push_back(size);
  }
  for (std::uint64_t w : words) {
    if (header64) out.header.append(reinterpret_cast<const char*>(&w), 8);
    else {
      const auto w32 = static_cast<std::uint32_t>(w);
      out.header.append(reinterpret_cast<const char*>(&w32), 4);
    }
  }
  return out;
}

// ---- payloads -----------------------------------------------------------------

namespace {

// Reads header words and payload bytes from an inline base64 text, an appended
// base64 text or raw appended bytes, with the position for error messages.
class PayloadSource {
 public:
  PayloadSource(const VtkXml& file, std::string name, std::string_view bytes, bool base64, std::size_t place,
                bool place_is_byte)
      : file_(file), name_(std::move(name)), raw_(bytes), b64_(bytes), base64_(base64), place_(place),
        place_is_byte_(place_is_byte) {}

  [[noreturn]] void fail(const std::string& what) const {
    const std::string msg = "DataArray '" + name_ + "': " + what;
    if (place_is_byte_) file_.fail_byte(place_, msg);
    file_.fail(place_, msg);
  }
  std::size_t max_remaining() const { return base64_ ? b64_.max_remaining() : raw_.size() - at_; }
  // Up to n bytes as a view into the file (raw) or into `storage` (base64),
  // fewer only at the end of the data.
  std::string_view take_up_to(std::size_t n, std::string& storage) {
    if (!base64_) {
      n = std::min(n, raw_.size() - at_);
      at_ += n;
      return raw_.substr(at_ - n, n);
    }
    const std::size_t start = storage.size();
    const auto got = b64_.read(std::min(n, max_remaining()), storage);
    if (!got) fail("invalid base64 data");
    return std::string_view(storage).substr(start, *got);
  }
  // Exactly n bytes, else "<what> runs past the end of the data".
  std::string_view take(std::size_t n, std::string& storage, const char* what) {
    const std::string_view v = take_up_to(n, storage);
    if (v.size() < n) fail(std::string(what) + " runs past the end of the data");
    return v;
  }
  std::uint64_t word(bool header64, const char* what) {
    std::string tmp;
    const std::string_view w = take(header64 ? 8 : 4, tmp, what);
    if (header64) { std::uint64_t v; std::memcpy(&v, w.data(), 8); return v; }
    std::uint32_t v;
    std::memcpy(&v, w.data(), 4);
    return v;
  }
  // What remains, counted (for "header says N bytes but M follow").
  std::size_t count_rest() {
    if (!base64_) return raw_.size() - at_;
    std::string sink;
    std::size_t n = 0;
    while (auto got = b64_.read(4096, sink)) {
      if (*got == 0) break;
      n += *got;
      sink.clear();
    }
    return n;
  }

 private:
  const VtkXml& file_;
  std::string name_;
  std::string_view raw_;
  Base64Reader b64_;
  bool base64_;
  std::size_t at_ = 0, place_;
  bool place_is_byte_;
};

// [count][bytes] or the zlib header and blocks, as the payload's bytes.
std::string_view read_payload(PayloadSource& src, bool header64, bool zlib, Scalar type, std::string& storage) {
  const std::string tname(scalar_name(type));
  if (!zlib) {
    const std::uint64_t nbytes = src.word(header64, "the size header");
    const std::string_view data = src.take_up_to(std::min<std::uint64_t>(nbytes, src.max_remaining()), storage);
    if (data.size() < nbytes)
      src.fail("size header says " + std::to_string(nbytes) + " bytes but " +
               std::to_string(data.size() + src.count_rest()) + " bytes of " + tname + " follow");
    if (nbytes % scalar_bytes(type))
      src.fail("size header says " + std::to_string(nbytes) + " bytes, not a whole number of " + tname);
    return data;
  }
  const std::uint64_t nblocks = src.word(header64, "the compression header");
  const std::uint64_t block = src.word(header64, "the compression header");
  const std::uint64_t last = src.word(header64, "the compression header");
  if (nblocks > src.max_remaining() / (header64 ? 8 : 4))
    src.fail("compression header announces " + std::to_string(nblocks) + " blocks, more than the data holds");
  if (last > block || (nblocks > 0 && block == 0))
    src.fail("compression header: last block size " + std::to_string(last) + " exceeds block size " + std::to_string(block));
  std::vector<std::uint64_t> sizes(nblocks);
  std::uint64_t total_in = 0;
  for (std::uint64_t& s : sizes) {
    s = src.word(header64, "the compression header");
    if (s > src.max_remaining()) src.fail("compressed block size " + std::to_string(s) + " exceeds the data");
    total_in += s;
  }
  if (total_in > src.max_remaining()) src.fail("compressed blocks (" + std::to_string(total_in) + " bytes) exceed the data");
  std::string compressed;
  const std::string_view in = src.take(total_in, compressed, "the compressed blocks");
  std::size_t at = 0;
  for (std::uint64_t b = 0; b < nblocks; ++b) {
    // VTK: every block has `block` bytes but the last, which has `last` (0: full).
    const std::uint64_t want = (b + 1 == nblocks && last != 0) ? last : block;
    if (want > kMaxZlibRatio * sizes[b] + 64)
      src.fail("zlib block " + std::to_string(b) + " claims " + std::to_string(want) + " bytes from " +
               std::to_string(sizes[b]) + " compressed bytes");
    const std::size_t out_at = storage.size();
    storage.resize(out_at + want);
    uLongf got = static_cast<uLongf>(want);
    const int rc = uncompress(reinterpret_cast<Bytef*>(storage.data() + out_at), &got,
                              reinterpret_cast<const Bytef*>(in.data() + at), static_cast<uLong>(sizes[b]));
    if (rc != Z_OK || got != want)
      src.fail("zlib block " + std::to_string(b) + " does not inflate to its " + std::to_string(want) + " bytes");
    at += sizes[b];
  }
  if (storage.size() % scalar_bytes(type))
    src.fail("uncompressed size " + std::to_string(storage.size()) + " is not a whole number of " + tname);
  return storage;
}

}  // namespace

std::string_view VtkXml::inline_payload(const Element& a, std::string& storage) const {
  PayloadSource src(*this, array_name(a), a.text, true, a.text_pos, false);
  return read_payload(src, header64_, zlib_, array_type(a), storage);
}

std::string_view VtkXml::appended_payload(const Element& a, std::string& storage) const {
  if (!appended_) fail(a.begin, "DataArray '" + array_name(a) + "' is appended but the file has no <AppendedData>");
  const auto off = a.attr("offset");
  if (!off) fail(a.begin, "appended DataArray '" + array_name(a) + "' has no offset");
  std::uint64_t offset = 0;
  const auto r = std::from_chars(off->data(), off->data() + off->size(), offset);
  const auto [begin, end] = *appended_;
  if (r.ec != std::errc() || r.ptr != off->data() + off->size() || offset > end - begin)
    fail(a.begin, "DataArray '" + array_name(a) + "': offset '" + quoted(*off) + "' is not within the " +
                      std::to_string(end - begin) + " bytes of AppendedData");
  PayloadSource src(*this, array_name(a), bytes_.substr(begin + offset, end - begin - offset), appended_base64_,
                    begin + offset, true);
  return read_payload(src, header64_, zlib_, array_type(a), storage);
}

std::string_view VtkXml::payload(const Element& a, std::string& storage) const {
  const std::string_view format = a.attr("format").value_or("ascii");
  if (format == "binary") return inline_payload(a, storage);
  if (format == "appended") return appended_payload(a, storage);
  fail(a.begin, "unknown DataArray format '" + quoted(format) + "'");
}

// ---- values -------------------------------------------------------------------

std::string VtkXml::array_name(const Element& a) const { return std::string(a.attr("Name").value_or("(unnamed)")); }

Scalar VtkXml::array_type(const Element& a) const {
  const std::string_view t = a.attr("type").value_or("");
  for (std::size_t i = 0; i < kScalars.size(); ++i)
    if (kScalars[i].name == t) return static_cast<Scalar>(i);
  fail(a.begin, "DataArray '" + array_name(a) + "' has unknown type '" + quoted(t) + "'");
}

std::int64_t VtkXml::components(const Element& a) const {
  const auto nc = a.attr("NumberOfComponents");
  if (!nc) return 1;
  TextCursor cur(*nc, source_);
  cur.set_first_line(line_at(a.begin));
  return cur.integer_in("NumberOfComponents", 1, 1000);
}

// Ascii text: each token a number of the array's type (integers must fit it).
template <class T>
void VtkXml::parse_ascii(const Element& a, std::vector<T>& out) const {
  const Scalar type = array_type(a);
  const char* p = a.text.data();
  const char* end = p + a.text.size();
  auto bad = [&](const char* at, const std::string& what) {
    const char* stop = std::find_if(at, end, is_space);
    fail(a.text_pos + static_cast<std::size_t>(at - a.text.data()),
         "DataArray '" + array_name(a) + "': " + what + " (" + quoted(std::string_view(at, stop - at)) + ")");
  };
  while (true) {
    while (p < end && is_space(*p)) ++p;
    if (p == end) break;
    std::from_chars_result r;
    if (scalar_is_integer(type)) {
      std::int64_t v = 0;
      if (type == Scalar::UInt64 && *p != '-') {
        std::uint64_t u = 0;
        r = std::from_chars(p, end, u);
        if (u > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) bad(p, "value too large");
        v = static_cast<std::int64_t>(u);
      } else {
        r = std::from_chars(p, end, v);
      }
      if (r.ec != std::errc() || (r.ptr < end && !is_space(*r.ptr))) bad(p, "not an integer");
      with_scalar(type, [&](auto t) {
        using S = decltype(t);
        if constexpr (std::is_integral_v<S>) {
          const std::int64_t lo = std::is_signed_v<S> ? static_cast<std::int64_t>(std::numeric_limits<S>::min()) : 0;
          const bool fits = v >= lo && (sizeof(S) == 8 || v <= static_cast<std::int64_t>(std::numeric_limits<S>::max()));
          if (!fits) bad(p, "value out of range of " + std::string(scalar_name(type)));
        }
      });
      if constexpr (std::is_same_v<T, double>) out.push_back(static_cast<double>(v));
      else out.push_back(v);
    } else {
      double v = 0;
      r = std::from_chars(p, end, v);
      if (r.ec != std::errc() || (r.ptr < end && !is_space(*r.ptr)) || !std::isfinite(v)) bad(p, "not a finite number");
      if constexpr (std::is_same_v<T, double>) out.push_back(v);
      else bad(p, "not an integer");
    }
    p = r.ptr;
  }
}

template <class T>
void VtkXml::convert(const Element& a, std::vector<T>& out) const {
  const Scalar type = array_type(a);
  if constexpr (std::is_integral_v<T>)
    if (!scalar_is_integer(type))
      fail(a.begin, "DataArray '" + array_name(a) + "' must have an integer type (not " + std::string(scalar_name(type)) + ")");
  if (a.attr("format").value_or("ascii") == "ascii") {
    parse_ascii(a, out);
  } else {
    std::string storage;
    const std::string_view raw = payload(a, storage);
    with_scalar(type, [&](auto t) {
      using S = decltype(t);
      const std::size_t n = raw.size() / sizeof(S);
      out.resize(n);
      if constexpr (std::is_same_v<S, T>) {
        if (n) std::memcpy(out.data(), raw.data(), n * sizeof(S));
      } else {
        for (std::size_t i = 0; i < n; ++i) {
          S v;
          std::memcpy(&v, raw.data() + i * sizeof(S), sizeof(S));
          if constexpr (std::is_same_v<S, std::uint64_t>)
            if (v > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
              fail(a.begin, "DataArray '" + array_name(a) + "': UInt64 value " + std::to_string(v) + " too large");
          out[i] = static_cast<T>(v);
        }
      }
      if constexpr (std::is_floating_point_v<S>)
        for (std::size_t i = 0; i < n; ++i)
          if (!std::isfinite(out[i]))
            fail(a.begin, "DataArray '" + array_name(a) + "': value " + std::to_string(i) + " is not finite");
    });
  }
  const std::int64_t nc = components(a);
  if (out.size() % static_cast<std::size_t>(nc) != 0)
    fail(a.begin, "DataArray '" + array_name(a) + "' size " + std::to_string(out.size()) + " is not a multiple of its " +
                      std::to_string(nc) + " components");
}

std::vector<std::int64_t> VtkXml::integers(const Element& a) const {
  std::vector<std::int64_t> out;
  convert(a, out);
  return out;
}

std::vector<double> VtkXml::reals(const Element& a) const {
  std::vector<double> out;
  convert(a, out);
  return out;
}

std::vector<std::int64_t> VtkXml::integers_in(const Element& a, std::int64_t lo, std::int64_t hi) const {
  std::vector<std::int64_t> out = integers(a);
  for (std::size_t i = 0; i < out.size(); ++i)
    if (out[i] < lo || out[i] > hi)
      fail(a.begin, "DataArray '" + array_name(a) + "': value " + std::to_string(out[i]) + " at index " +
                        std::to_string(i) + " out of range (" + std::to_string(lo) + ".." + std::to_string(hi) + ")");
  return out;
}

}  // namespace polydual::io::vtkxml
