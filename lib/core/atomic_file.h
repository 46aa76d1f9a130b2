// Atomic output: write to a temporary file beside the target, then rename, so a
// failure never leaves a half-written output.
#pragma once
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

namespace polydual {

// Calls write(stream) on a temporary file next to `path` and renames it to
// `path` if write returns without throwing and the stream is good. Otherwise the
// temporary is removed and the error is rethrown (std::runtime_error naming
// `path` when the stream failed).
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write, bool binary = false);

// Same for a directory tree (e.g. an OpenFOAM case): fill(tmpdir) writes into a
// fresh temporary directory which then replaces `dir` (an existing `dir` is
// removed only after fill succeeded).
void write_directory_atomically(const std::filesystem::path& dir,
                                const std::function<void(const std::filesystem::path&)>& fill);

}  // namespace polydual
