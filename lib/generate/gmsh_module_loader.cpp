// gmsh_module::gmsh_api() for the polydual command: loads polydual-gmsh.so
// with dlopen on first use, so that only `generate` and `demo` pay for Gmsh
// and OpenCASCADE (and the other commands run where libgmsh is absent).
//
// Where the module is looked for, in this order:
//   1. $POLYDUAL_GMSH_MODULE, when set (that file only);
//   2. beside the executable (the build tree: build/polydual-gmsh.so);
//   3. the install tree: <bindir>/POLYDUAL_GMSH_MODULE_RELDIR (set by CMake,
//      "../lib/polydual" for the default layout), relative to the executable.
// The module is never unloaded (Gmsh keeps global state until exit).
#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "generate/gmsh_module.h"

#ifndef POLYDUAL_GMSH_MODULE_RELDIR
#error "POLYDUAL_GMSH_MODULE_RELDIR: the installed module's directory relative to the executable's"
#endif

namespace polydual::gmsh_module {

namespace {

constexpr const char* kModuleFile = "polydual-gmsh.so";

std::vector<std::filesystem::path> candidate_paths() {
  if (const char* env = std::getenv("POLYDUAL_GMSH_MODULE"); env && *env) return {env};
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  const std::filesystem::path dir = exe.parent_path();
  return {dir / kModuleFile, (dir / POLYDUAL_GMSH_MODULE_RELDIR / kModuleFile).lexically_normal()};
}

std::string joined(const std::vector<std::filesystem::path>& paths) {
  std::string s;
  for (const auto& p : paths) s += (s.empty() ? "" : ", ") + p.string();
  return s.empty() ? "(the executable's directory is unknown)" : s;
}

const GmshApi* open_module(const std::filesystem::path& path) {
  void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = ::dlerror();
    throw std::runtime_error("cannot load the Gmsh module " + path.string() + ": " + (why ? why : "dlopen failed"));
  }
  using Entry = const GmshApi* (*)();
  auto entry = reinterpret_cast<Entry>(::dlsym(handle, "polydual_gmsh_module_api"));
  const GmshApi* api = entry ? entry() : nullptr;
  if (!api) throw std::runtime_error(path.string() + " is not a polydual Gmsh module (no polydual_gmsh_module_api)");
  if (api->abi_version != kAbiVersion)
    throw std::runtime_error(path.string() + " is a Gmsh module of ABI version " + std::to_string(api->abi_version) +
                             ", this polydual needs version " + std::to_string(kAbiVersion) +
                             " (a module from another build)");
  return api;
}

const GmshApi& load() {
  const std::vector<std::filesystem::path> paths = candidate_paths();
  for (const auto& p : paths) {
    std::error_code ec;
    if (std::filesystem::exists(p, ec)) return *open_module(p);
  }
  throw std::runtime_error(std::string("the Gmsh module ") + kModuleFile +
                           ", which `generate` and `demo` need, was not found; looked for " + joined(paths) +
                           " (it is built and installed with polydual; POLYDUAL_GMSH_MODULE names another path)");
}

}  // namespace

const GmshApi& gmsh_api() {
  // A failed load is retried on the next call (call_once rethrows and stays unset).
  static std::once_flag once;
  static const GmshApi* api = nullptr;
  std::call_once(once, [] { api = &load(); });
  return *api;
}

}  // namespace polydual::gmsh_module
