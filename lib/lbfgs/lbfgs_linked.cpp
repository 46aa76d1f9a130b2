// lbfgs_module::lbfgs_api() for programs linked with Ceres (polydual::polydual):
// the table of lbfgs_ceres.cpp, in the same binary.
#include "lbfgs/lbfgs_module.h"

namespace polydual::lbfgs_module {

const LbfgsApi& lbfgs_api() { return *polydual_lbfgs_module_api(); }

}  // namespace polydual::lbfgs_module
