// Running a shell command (the polydual binary, python) from a test and
// collecting its output and exit code; shared by the tests that drive the
// command end to end.
#pragma once
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace polydual::testing {

// Runs `cmd` through the shell; returns its stdout, sets its exit code (-1
// when it did not exit normally).
inline std::string capture(const std::string& cmd, int& code) {
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  std::array<char, 4096> buf;
  while (std::size_t n = std::fread(buf.data(), 1, buf.size(), p)) out.append(buf.data(), n);
  const int status = pclose(p);
  code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

struct CmdResult {
  int code;
  std::string out;  // stdout + stderr
};

// `polydual ARGS` with stderr merged into stdout.
inline CmdResult run_polydual(const std::string& args) {
  CmdResult r{0, {}};
  r.out = capture(std::string(POLYDUAL_BINARY) + " " + args + " 2>&1", r.code);
  return r;
}

}  // namespace polydual::testing
