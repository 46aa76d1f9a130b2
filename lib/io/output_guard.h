// What polydual may replace (and what it must leave alone) when it writes an
// output: the command calls check_output_target before any work, so a refused
// output costs nothing; the writers apply the same rules again when writing.
//
//  - An output that is one of the inputs (the same file by any name: symbolic
//    links, hard links, "..") is refused.
//  - A file output (.vtu, .msh, ...) replaces an existing regular file whose
//    name has the output's extension (reruns); an existing directory, or a
//    file of another kind (`-o mesh.msh` when VTU is written), is refused
//    unless `force`.
//  - An OpenFOAM case is written into OUT/constant/polyMesh (and a minimal
//    OUT/system when OUT has none); everything else in OUT is left as it was.
//    OUT must not exist, be empty, or already be a case (has constant/ or
//    system/); any other directory is refused unless `force`; OUT being a
//    file is refused.
//  - Never through a link: an output path that is a symbolic link (to
//    anything), or a case whose constant/, constant/polyMesh or system/ is
//    one, is refused even with `force`; so are FIFOs, devices and sockets.
//  - A new output's parent directory must exist (files and cases alike), and
//    every name component must fit NAME_MAX with room for the temporary's
//    suffix.
#pragma once
#include <span>
#include <string>

namespace polydual {

enum class OutputKind {
  File,      // one file, replaced atomically
  FoamCase,  // an OpenFOAM case directory (OUT/constant/polyMesh)
};

// Throws UsageError (exit 2) with a message naming the path and the reason
// when writing `out` of `kind` could lose data the user owns. `extension`
// (e.g. ".vtu"; empty: any) is the file format's: an existing file with
// another extension is not replaced without `force`. `force` never allows
// replacing an input, a directory by a file, or a file by a case.
void check_output_target(std::span<const std::string> inputs, const std::string& out, OutputKind kind,
                         bool force, const std::string& extension = "");

// An output directory (a case, the demo's): UsageError when `dir` is a link,
// exists and is not a directory, or does not exist and neither does its
// parent. Returns whether it exists.
bool check_output_directory(const std::string& dir);

// The case rules alone (used by write_foam): UsageError unless `case_dir`
// does not exist, is empty, is a case, or `force` and a directory.
void check_case_directory(const std::string& case_dir, bool force);

}  // namespace polydual
