// Opening and reading input files. Every reader parses bytes in memory (so
// the fuzzers and the tests call exactly the code the files use); these
// helpers decide what may be read and how much of it is read:
//   - only regular files (a link to one is followed): a directory, FIFO,
//     device, socket or dangling link is refused with its own reason, and
//     opening never blocks (a FIFO without a writer is refused, not waited on);
//   - InputFile loads a file on demand, in chunks, into storage allocated
//     once for its size and left untouched: a reader that stops at a bad
//     header or a NUL byte has read (and made resident) little more than what
//     it looked at, however large the file claims to be.
#pragma once
#include <cstdint>
#include <string>
#include <memory>
#include <string_view>

namespace polydual::io {

// Throws InputError(path, "", reason) unless `path` names a regular file (or a
// link to one): "cannot open file (no such file or directory)", "is a
// directory; polydual reads only regular files", "is a FIFO (named pipe);
// ...", "is a dangling symbolic link (to 'T')", "is a character device; ...".
void require_regular_file(const std::string& path);

// A regular file opened for reading (O_NONBLOCK, type checked before and
// after the open), loaded on demand.
class InputFile {
 public:
  explicit InputFile(const std::string& path);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  const std::string& path() const { return path_; }
  // The size at open (smaller once a read found the file ended earlier).
  std::uint64_t size() const { return size_; }
  // The bytes loaded so far, from the start of the file. Views of them stay
  // valid while this object lives: the storage never moves.
  std::string_view loaded() const { return {data_, loaded_}; }
  // Loads on until `end` bytes are loaded or the file ends (reading ahead in
  // chunks that grow with what is loaded, at most 64 MiB each); returns
  // loaded(). Throws InputError when reading fails or when the file turns out
  // longer than its size at open (it is still being written).
  std::string_view load_to(std::uint64_t end);
  std::string_view load_all() { return load_to(size_); }
  // Up to `n` bytes ending at the file's end, read without loading the rest.
  std::string tail(std::size_t n) const;

 private:
  void read_into(std::uint64_t end);
  void check_not_longer();
  std::string path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
  std::unique_ptr<char[]> storage_;  // size_ bytes, resident only where loaded
  char* data_ = nullptr;
  std::size_t loaded_ = 0;
  bool checked_end_ = false;
};

// The whole of `path` (a regular file, as require_regular_file) in one
// string; for readers that need every byte anyway.
std::string read_file_bytes(const std::string& path);

// What a NUL byte in text is called in errors.
inline constexpr const char* kNulInText = "NUL byte where text was expected (a binary or zero-filled file?)";
// The line (1-based) of byte `pos` in `bytes` and the InputError for a NUL
// byte there in a text format ("line N: " + kNulInText).
std::size_t line_of(std::string_view bytes, std::size_t pos);
[[noreturn]] void fail_nul_byte(const std::string& source, std::string_view bytes, std::size_t pos);

}  // namespace polydual::io
