// Whole-file reads for the readers' file helpers: every reader parses a memory
// buffer (so the fuzzers and the tests call exactly the code the files use).
#pragma once
#include <string>

namespace polydual::io {

// The bytes of `path`; InputError(path, "", "cannot open file") when it cannot
// be read.
std::string read_file_bytes(const std::string& path);
// True when `path` names a readable regular file.
bool file_exists(const std::string& path);

}  // namespace polydual::io
