// The boundary between polydual and Ceres' solver. The global scheme
// (optim/global_ceres.cpp) minimises its objective by L-BFGS behind this
// table; Ceres' solver, with the BLAS, LAPACK, SuiteSparse, glog and gflags
// libraries it links, lives in lbfgs_ceres.cpp alone. The library
// (polydual::polydual) links that file directly (lbfgs_linked.cpp); the
// polydual command builds it as a module (polydual-lbfgs.so) that only
// `--optimize global` loads with dlopen (cli/lbfgs_module_loader.cpp), so
// that every other run starts without those ~20 shared libraries (~2.5 MB of
// resident memory; measured with /proc/<pid>/smaps at 100k tets).
// (ceres::Jet, header-only, is used everywhere else and costs nothing.)
//
// Plain data and function pointers only, no exceptions across the table; a
// stale module is refused by its ABI version.
#pragma once
#include <cstddef>
#include <string>

namespace polydual::lbfgs_module {

// Bump whenever LbfgsApi, Problem or Options change.
inline constexpr int kAbiVersion = 1;

// f: R^n -> R with its gradient. evaluate writes f(x) to *cost and, when
// gradient is not null, its gradient; it returns false where f is not
// defined (the line search then backs off).
struct Problem {
  std::size_t n = 0;
  void* user = nullptr;
  bool (*evaluate)(void* user, const double* x, double* cost, double* gradient) = nullptr;
};

struct Options {
  int max_iterations = 0;
  double function_tolerance = 1e-12;
  double parameter_tolerance = 1e-12;
};

struct LbfgsApi {
  int abi_version;  // first member (core/module_loader.h reads it)
  // Minimises from x (n values, overwritten by the result) by L-BFGS with a
  // line search, at most options.max_iterations iterations; x is the best
  // point found whatever the solver's termination. Returns false with a
  // message in `error` only when the solver could not run (an exception
  // inside it).
  bool (*minimize)(const Problem& problem, const Options& options, double* x, std::string& error);
};

// The table: linked in (polydual::polydual) or loaded from polydual-lbfgs.so
// (the command). The loader throws std::runtime_error naming the places it
// looked in when the module is missing, cannot be loaded or is stale.
const LbfgsApi& lbfgs_api();

}  // namespace polydual::lbfgs_module

// The module's one exported symbol (also defined when linked in).
extern "C" const polydual::lbfgs_module::LbfgsApi* polydual_lbfgs_module_api();
