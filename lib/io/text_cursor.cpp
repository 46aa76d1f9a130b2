#include "io/text_cursor.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>

#include "io/file_bytes.h"

namespace polydual::io {

std::string quoted(std::string_view token) {
  std::string s;
  for (char c : token.substr(0, 40)) s += (c >= 32 && c < 127) ? c : '?';
  if (token.size() > 40) s += "...";
  return s;
}

static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

// The bytes that end a token: blanks and NUL (a comment character too, per
// cursor).
static constexpr auto kEndsToken = [] {
  std::array<bool, 256> t{};
  for (unsigned char c : {' ', '\t', '\r', '\n', '\f', '\v', '\0'}) t[c] = true;
  return t;
}();

TextCursor::TextCursor(std::string_view bytes, std::string source, char comment)
    : bytes_(bytes), source_(std::move(source)), comment_(comment) {
  skip_byte_order_mark();
}

TextCursor::TextCursor(InputFile& file, char comment)
    : bytes_(file.loaded()), file_(&file), source_(file.path()), comment_(comment) {
  skip_byte_order_mark();
}

// Editors on Windows may start UTF-8 text with EF BB BF; it is not content.
void TextCursor::skip_byte_order_mark() {
  if (have(2) && bytes_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;
}

bool TextCursor::load(std::size_t end) {
  bytes_ = file_->load_to(end);
  return end <= bytes_.size();
}

std::size_t TextCursor::total() const { return file_ ? static_cast<std::size_t>(file_->size()) : bytes_.size(); }

void TextCursor::fail_nul() const {
  throw InputError(source_, binary_ ? byte_place() : "line " + std::to_string(line_), kNulInText);
}

// Over a file the loops run on what is loaded, then load on and resume.
void TextCursor::skip_blanks() {
  bool in_comment = false;
  do {
    const char* d = bytes_.data();
    const std::size_t n = bytes_.size();
    for (; pos_ < n; ++pos_) {
      const char c = d[pos_];
      if (c == '\n') {
        ++line_;
        in_comment = false;
      } else if (in_comment) {
        if (c == '\0') return;  // token() reports it
      } else if (c == comment_ && c != '\0') {
        in_comment = true;
      } else if (!is_space(c)) {
        return;
      }
    }
  } while (file_ && load(pos_ + 1));
}

bool TextCursor::at_end() {
  skip_blanks();
  return !have(pos_);
}

std::string_view TextCursor::token(const char* what) {
  skip_blanks();
  token_line_ = line_;
  if (!have(pos_)) fail(std::string("file ends while reading ") + what);
  const std::size_t start = pos_;
  do {
    const char* d = bytes_.data();
    const std::size_t n = bytes_.size();
    while (pos_ < n && !kEndsToken[static_cast<unsigned char>(d[pos_])] && d[pos_] != comment_) ++pos_;
  } while (pos_ == bytes_.size() && file_ && load(pos_ + 1));
  if (pos_ < bytes_.size() && bytes_[pos_] == '\0') fail_nul();  // "Tet\0ahedra" is no keyword "Tet"
  return bytes_.substr(start, pos_ - start);
}

std::string_view TextCursor::peek() {
  const std::size_t pos = pos_, line = line_, tline = token_line_;
  skip_blanks();
  std::string_view t;
  if (have(pos_)) t = token("");
  pos_ = pos;
  line_ = line;
  token_line_ = tline;
  return t;
}

std::int64_t TextCursor::integer(const char* what) {
  std::string_view t = token(what);
  std::string_view digits = (!t.empty() && t[0] == '+') ? t.substr(1) : t;
  std::int64_t v = 0;
  auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
  if (ec == std::errc::result_out_of_range) fail(std::string(what) + " is out of range (" + quoted(t) + ")");
  if (ec != std::errc() || end != digits.data() + digits.size() || digits.empty())
    fail(std::string("expected ") + what + " (an integer), got '" + quoted(t) + "'");
  return v;
}

double TextCursor::real(const char* what) {
  std::string_view t = token(what);
  std::string_view digits = (!t.empty() && t[0] == '+') ? t.substr(1) : t;
  double v = 0;
  auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
  // Out of range means overflow to infinity (or underflow, which is harmless
  // but from_chars reports both the same way): treat as not finite only when
  // the magnitude is huge.
  if (ec == std::errc::result_out_of_range && end == digits.data() + digits.size()) {
    const double d = std::strtod(std::string(digits).c_str(), nullptr);
    if (std::isfinite(d)) return d;
    fail(std::string(what) + " is not finite (" + quoted(t) + ")");
  }
  if (ec != std::errc() || end != digits.data() + digits.size() || digits.empty())
    fail(std::string("expected ") + what + " (a number), got '" + quoted(t) + "'");
  if (!std::isfinite(v)) fail(std::string(what) + " is not finite (" + quoted(t) + ")");
  return v;
}

std::int64_t TextCursor::integer_in(const char* what, std::int64_t lo, std::int64_t hi) {
  const std::int64_t v = integer(what);
  if (v < lo || v > hi)
    fail(std::string(what) + " " + std::to_string(v) + " out of range (" + std::to_string(lo) + ".." +
         std::to_string(hi) + ")");
  return v;
}

std::string_view TextCursor::rest_of_line() {
  const std::size_t start = pos_;
  token_line_ = line_;
  while (have(pos_) && bytes_[pos_] != '\n') {
    if (bytes_[pos_] == '\0') fail_nul();
    ++pos_;
  }
  std::string_view s = bytes_.substr(start, pos_ - start);
  if (have(pos_)) {
    ++pos_;
    ++line_;
  }
  if (!s.empty() && s.back() == '\r') s.remove_suffix(1);
  return s;
}

bool TextCursor::line_is_empty() {
  std::size_t p = pos_;
  while (have(p) && bytes_[p] != '\n') {
    const char c = bytes_[p];
    if (comment_ != '\0' && c == comment_) return true;
    if (!is_space(c)) return false;
    ++p;
  }
  return true;
}

void TextCursor::check_count(std::uint64_t count, std::size_t min_bytes, const char* what) {
  if (count > remaining() / (min_bytes == 0 ? 1 : min_bytes))
    fail("file too short for " + std::to_string(count) + " " + what + " records (at least " +
         std::to_string(count * min_bytes) + " bytes, " + std::to_string(remaining()) + " remain)");
}

void TextCursor::skip_end_of_line() {
  while (have(pos_) && (bytes_[pos_] == ' ' || bytes_[pos_] == '\t' || bytes_[pos_] == '\r')) ++pos_;
  if (!have(pos_) || bytes_[pos_] != '\n') fail_byte("expected the end of a line before binary data");
  ++pos_;
  ++line_;
}

const char* TextCursor::take(std::size_t n, const char* what) {
  if (n > bytes_.size() - pos_ && (n > remaining() || !have(pos_ + n - 1)))
    fail_byte(std::string("file ends inside ") + what);
  const char* p = bytes_.data() + pos_;
  pos_ += n;
  return p;
}

std::size_t TextCursor::find(std::string_view needle) {
  std::size_t from = pos_;
  while (true) {
    const std::size_t at = bytes_.find(needle, from);
    if (at != std::string_view::npos) return at;
    // Not in what is loaded: load as much again and search on from where a
    // match could still begin.
    const std::size_t had = bytes_.size();
    if (!file_ || (load(2 * had + 1), bytes_.size() == had)) return std::string_view::npos;
    from = std::max(pos_, had >= needle.size() ? had - needle.size() + 1 : 0);
  }
}

void TextCursor::seek(std::size_t pos) {
  // Recount lines up to pos: binary files rarely need lines after a seek, but
  // the text sections that follow do.
  for (std::size_t i = pos_; i < pos && i < bytes_.size(); ++i)
    if (bytes_[i] == '\n') ++line_;
  pos_ = pos < bytes_.size() ? pos : bytes_.size();
}

void TextCursor::fail(const std::string& what) const {
  throw InputError(source_, binary_ ? byte_place() : line_place(), what);
}
void TextCursor::fail_byte(const std::string& what) const { throw InputError(source_, byte_place(), what); }

}  // namespace polydual::io
