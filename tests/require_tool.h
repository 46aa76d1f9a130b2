// Tests that need a program from outside the build (gmsh, tetgen, checkMesh,
// /usr/bin/python3 with a module, a CGAL Mesh_3 generator): where it is
// missing the test is skipped with a message, unless the environment sets
// POLYDUAL_REQUIRE_TOOLS=1 (scripts/test.sh does: CI installs every tool),
// which turns the skip into a failure so that a broken install cannot pass
// as a green run with nothing tested.
#pragma once
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace polydual::test {

// Whether a missing tool fails the test (POLYDUAL_REQUIRE_TOOLS=1).
inline bool tools_required() {
  const char* v = std::getenv("POLYDUAL_REQUIRE_TOOLS");
  return v != nullptr && std::string(v) == "1";
}

// Whether `name` is a command on PATH.
inline bool have_command(const std::string& name) {
  return std::system(("command -v '" + name + "' > /dev/null 2>&1").c_str()) == 0;
}

// Whether /usr/bin/python3 (Debian's, where the python3-* packages install)
// imports `module`.
inline bool have_python_module(const std::string& module) {
  return std::system(("/usr/bin/python3 -c 'import " + module + "' > /dev/null 2>&1").c_str()) == 0;
}

}  // namespace polydual::test

// Ends the current test because a tool is missing: skipped, or failed under
// POLYDUAL_REQUIRE_TOOLS=1. `message` is streamed (it may use <<) and should
// name the tool and its package. Usable where GTEST_SKIP is (a void function).
#define POLYDUAL_MISSING_TOOL(message)                                                  \
  do {                                                                                  \
    if (::polydual::test::tools_required())                                             \
      GTEST_FAIL() << message << " (POLYDUAL_REQUIRE_TOOLS=1: a missing tool fails)";   \
    else                                                                                \
      GTEST_SKIP() << message;                                                          \
  } while (0)
