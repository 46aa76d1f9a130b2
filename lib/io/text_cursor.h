// A cursor over an in-memory file for the hand-written readers: whitespace
// separated tokens with the line they came from, plus raw byte access for the
// binary parts of Gmsh files. Every failure becomes an InputError naming the
// source and the place ("line N" in text, "byte N" in binary data), so the
// readers never need their own bookkeeping of positions.
//
// Over a file (io/file_bytes.h) the cursor loads the bytes as it reaches
// them, so a reader that fails early has read little of a huge file. A UTF-8
// byte-order mark at the start is skipped. A NUL byte where text is expected
// (a token, a comment, the rest of a line) is an error at its place: text
// formats hold none, and a zero-filled file stops there.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "core/error.h"

namespace polydual::io {

class InputFile;

class TextCursor {
 public:
  // comment: a character that starts a comment running to the end of the line
  // ('#' for Medit and TetGen), or '\0' for none (Gmsh).
  TextCursor(std::string_view bytes, std::string source, char comment = '\0');
  // Over `file` (which must outlive the cursor), named by its path.
  explicit TextCursor(InputFile& file, char comment = '\0');

  // Skips whitespace and comments; true when nothing but those remains.
  bool at_end();
  // Next token; throws "file ends while reading <what>" at the end.
  std::string_view token(const char* what);
  // The next token without consuming it ("" at the end).
  std::string_view peek();
  // The next token parsed as an integer / a finite double ("line N: <what> is not
  // an integer (abc)", "line N: coordinate is not finite (nan)").
  std::int64_t integer(const char* what);
  double real(const char* what);
  // Integer in [lo, hi], else "<what> N out of range (lo..hi)".
  std::int64_t integer_in(const char* what, std::int64_t lo, std::int64_t hi);
  // The remainder of the current line (without the newline), consumed.
  std::string_view rest_of_line();
  // True when only blanks remain on the current line (comments count as blank).
  bool line_is_empty();

  // A count read from the file that announces `count` items of at least
  // `min_bytes` bytes each: fails unless that many bytes remain, so a header
  // claiming 10^12 nodes is an error and not a huge allocation.
  void check_count(std::uint64_t count, std::size_t min_bytes, const char* what);

  // Binary access (Gmsh binary files): skips exactly one "\n" (or "\r\n")
  // ending the current text line, then raw reads at the byte offset.
  void skip_end_of_line();
  template <class T>
  T binary(const char* what) {
    T v;
    std::memcpy(&v, take(sizeof(T), what), sizeof(T));
    return v;
  }
  const char* take(std::size_t n, const char* what);

  std::size_t line() const { return token_line_; }
  std::size_t offset() const { return pos_; }
  // Bytes after the cursor, counted to the end of the file (not only of
  // what is loaded).
  std::size_t remaining() const { return total() - pos_; }
  // The absolute offset of the next `needle` at or after the cursor
  // (loading on as needed), or npos.
  std::size_t find(std::string_view needle);
  const std::string& source() const { return source_; }
  // Numbers lines from `line` (for a cursor over a slice of a larger file).
  void set_first_line(std::size_t line) { line_ = token_line_ = line; }
  // Moves to an absolute byte offset (after find()).
  void seek(std::size_t pos);

  // In binary mode (Gmsh binary files after $MeshFormat) every failure names
  // the byte offset, since line numbers mean nothing inside binary data.
  void set_binary(bool binary) { binary_ = binary; }
  bool is_binary() const { return binary_; }

  std::string line_place() const { return "line " + std::to_string(token_line_); }
  std::string byte_place() const { return "byte " + std::to_string(pos_); }
  [[noreturn]] void fail(const std::string& what) const;       // at the last token's line (or byte)
  [[noreturn]] void fail_byte(const std::string& what) const;  // at the current byte

 private:
  void skip_blanks();
  void skip_byte_order_mark();
  // True when byte p exists (loading up to it from the file if needed).
  bool have(std::size_t p) { return p < bytes_.size() || (file_ && load(p + 1)); }
  bool load(std::size_t end);
  std::size_t total() const;
  [[noreturn]] void fail_nul() const;
  std::string_view bytes_;  // what is loaded (all of it for a memory buffer)
  InputFile* file_ = nullptr;
  std::string source_;
  char comment_;
  bool binary_ = false;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;        // line of pos_
  std::size_t token_line_ = 1;  // line of the last token read
};

// Decimal text of a token for messages, shortened so garbage stays readable.
std::string quoted(std::string_view token);

}  // namespace polydual::io
