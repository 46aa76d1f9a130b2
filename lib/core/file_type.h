// What kind of file a path names, without following a final symbolic link:
// the readers and the output guard refuse what is not a regular file (or a
// directory where one is expected) and say what it is instead.
#pragma once
#include <sys/types.h>

#include <string>

namespace polydual {

enum class FileType { Missing, Regular, Directory, Symlink, Fifo, CharDevice, BlockDevice, Socket, Unknown };

// lstat(2) of `path`: the type of the path itself (a link is Symlink).
// `error` gets errno when lstat fails for another reason than a missing
// entry (ENAMETOOLONG, EACCES, ELOOP, ENOTDIR); Missing is returned then too.
FileType file_type_no_follow(const std::string& path, int* error = nullptr);
// The same after following links (stat(2)); a dangling link is Missing.
FileType file_type_followed(const std::string& path);

// "a symbolic link", "a FIFO (named pipe)", "a character device", ...
const char* describe_file_type(FileType type);
FileType file_type_of_mode(mode_t mode);

// The target a symbolic link holds ("" when `path` is not one).
std::string link_target(const std::string& path);

}  // namespace polydual
