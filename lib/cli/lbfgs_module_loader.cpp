// lbfgs_module::lbfgs_api() for the polydual command: loads polydual-lbfgs.so
// with dlopen on first use (core/module_loader.h says where it looks), so that
// only `--optimize global` pays for Ceres' solver and its libraries.
#include <mutex>

#include "core/module_loader.h"
#include "lbfgs/lbfgs_module.h"

namespace polydual::lbfgs_module {

const LbfgsApi& lbfgs_api() {
  // A failed load is retried on the next call (call_once rethrows and stays unset).
  static std::once_flag once;
  static const LbfgsApi* api = nullptr;
  std::call_once(once, [] {
    api = static_cast<const LbfgsApi*>(modules::load_table({"polydual-lbfgs.so", "POLYDUAL_LBFGS_MODULE",
                                                            "polydual_lbfgs_module_api",
                                                            "the L-BFGS (Ceres) module",
                                                            "which `--optimize global` needs", kAbiVersion}));
  });
  return *api;
}

}  // namespace polydual::lbfgs_module
