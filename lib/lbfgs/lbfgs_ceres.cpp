// The L-BFGS table of lbfgs_module.h, by ceres::GradientProblemSolver. It
// links no polydual code (the module depends on Ceres and the C++ runtime).
#include <ceres/gradient_problem.h>
#include <ceres/gradient_problem_solver.h>

#include "lbfgs/lbfgs_module.h"

namespace polydual::lbfgs_module {
namespace {

class Function final : public ceres::FirstOrderFunction {
 public:
  explicit Function(const Problem& p) : p_(p) {}
  int NumParameters() const override { return static_cast<int>(p_.n); }
  bool Evaluate(const double* x, double* cost, double* gradient) const override {
    return p_.evaluate(p_.user, x, cost, gradient);
  }

 private:
  const Problem& p_;
};

bool minimize(const Problem& problem, const Options& options, double* x, std::string& error) {
  try {
    ceres::GradientProblem gp(new Function(problem));  // takes ownership
    ceres::GradientProblemSolver::Options opt;
    opt.line_search_direction_type = ceres::LBFGS;
    opt.max_num_iterations = options.max_iterations;
    opt.logging_type = ceres::SILENT;
    opt.minimizer_progress_to_stdout = false;
    opt.function_tolerance = options.function_tolerance;
    opt.parameter_tolerance = options.parameter_tolerance;
    ceres::GradientProblemSolver::Summary sum;
    ceres::Solve(opt, gp, x, &sum);  // x: the best point found, whatever the termination
    return true;
  } catch (const std::exception& e) {
    error = e.what();
    return false;
  }
}

constexpr LbfgsApi kApi{kAbiVersion, &minimize};

}  // namespace
}  // namespace polydual::lbfgs_module

extern "C" __attribute__((visibility("default"))) const polydual::lbfgs_module::LbfgsApi* polydual_lbfgs_module_api() {
  return &polydual::lbfgs_module::kApi;
}
