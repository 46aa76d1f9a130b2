#include "core/module_loader.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#ifndef POLYDUAL_GMSH_MODULE_RELDIR
#error "POLYDUAL_GMSH_MODULE_RELDIR: the installed modules' directory relative to the executable's"
#endif

namespace polydual::modules {

namespace {

std::vector<std::filesystem::path> candidate_paths(const ModuleSpec& spec) {
  if (const char* env = std::getenv(spec.env_var); env && *env) return {env};
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  const std::filesystem::path dir = exe.parent_path();
  return {dir / spec.file, (dir / POLYDUAL_GMSH_MODULE_RELDIR / spec.file).lexically_normal()};
}

std::string joined(const std::vector<std::filesystem::path>& paths) {
  std::string s;
  for (const auto& p : paths) s += (s.empty() ? "" : ", ") + p.string();
  return s.empty() ? "(the executable's directory is unknown)" : s;
}

const void* open_module(const ModuleSpec& spec, const std::filesystem::path& path) {
  void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = ::dlerror();
    throw std::runtime_error(std::string("cannot load ") + spec.what + " " + path.string() + ": " +
                             (why ? why : "dlopen failed"));
  }
  using Entry = const void* (*)();
  auto entry = reinterpret_cast<Entry>(::dlsym(handle, spec.entry));
  const void* table = entry ? entry() : nullptr;
  if (!table) throw std::runtime_error(path.string() + " is not " + spec.what + " (no " + spec.entry + ")");
  const int version = *static_cast<const int*>(table);
  if (version != spec.abi_version)
    throw std::runtime_error(path.string() + " is " + spec.what + " of ABI version " + std::to_string(version) +
                             ", this polydual needs version " + std::to_string(spec.abi_version) +
                             " (a module from another build)");
  return table;
}

}  // namespace

const void* load_table(const ModuleSpec& spec) {
  const std::vector<std::filesystem::path> paths = candidate_paths(spec);
  for (const auto& p : paths) {
    std::error_code ec;
    if (std::filesystem::exists(p, ec)) return open_module(spec, p);
  }
  throw std::runtime_error(std::string(spec.what) + " " + spec.file + ", " + spec.needed_by +
                           ", was not found; looked for " + joined(paths) +
                           " (it is built and installed with polydual; " + spec.env_var + " names another path)");
}

}  // namespace polydual::modules
