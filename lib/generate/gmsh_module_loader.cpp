// gmsh_module::gmsh_api() for the polydual command: loads polydual-gmsh.so
// with dlopen on first use (core/module_loader.h says where it looks), so that
// only `generate` and `demo` pay for Gmsh and OpenCASCADE (and the other
// commands run where libgmsh is absent). Gmsh keeps global state until exit:
// the module is never unloaded.
#include <mutex>

#include "core/module_loader.h"
#include "generate/gmsh_module.h"

namespace polydual::gmsh_module {

const GmshApi& gmsh_api() {
  // A failed load is retried on the next call (call_once rethrows and stays unset).
  static std::once_flag once;
  static const GmshApi* api = nullptr;
  std::call_once(once, [] {
    api = static_cast<const GmshApi*>(modules::load_table({"polydual-gmsh.so", "POLYDUAL_GMSH_MODULE",
                                                           "polydual_gmsh_module_api", "the Gmsh module",
                                                           "which `generate` and `demo` need", kAbiVersion}));
  });
  return *api;
}

}  // namespace polydual::gmsh_module
