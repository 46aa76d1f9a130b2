// Loading polydual's optional modules (polydual-gmsh.so, polydual-lbfgs.so)
// with dlopen, for the polydual command: each module carries a heavy
// dependency (Gmsh and OpenCASCADE; Ceres and its BLAS/LAPACK/SuiteSparse
// stack) that only some commands or options use, so that the others start
// without it (and run where it is absent).
//
// Where a module is looked for, in this order:
//   1. $<env_var>, when set (that file only);
//   2. beside the executable (the build tree: build/<file>);
//   3. the install tree: <bindir>/POLYDUAL_GMSH_MODULE_RELDIR (set by CMake,
//      "../lib/polydual" for the default layout), relative to the executable.
// A module is never unloaded.
#pragma once

namespace polydual::modules {

struct ModuleSpec {
  const char* file;       // "polydual-gmsh.so"
  const char* env_var;    // "POLYDUAL_GMSH_MODULE"
  const char* entry;      // the exported function returning the table
  const char* what;       // "the Gmsh module"
  const char* needed_by;  // "which `generate` and `demo` need"
  int abi_version;        // the table's first member must equal it
};

// The module's table (its first member an int ABI version equal to
// spec.abi_version). Throws std::runtime_error naming the places looked in
// when the module is missing, and the file when it cannot be loaded, has no
// entry or is of another ABI version.
const void* load_table(const ModuleSpec& spec);

}  // namespace polydual::modules
