// The convert pipeline as one function (used by `convert` and `demo`).
#pragma once
#include <string>

#include "classify/classify.h"
#include "cli/args.h"
#include "core/json.h"
#include "dual/build_dual.h"
#include "optim/optimize.h"

namespace polydual::cli {

struct ConvertOptions {
  ClassifyParams classify;
  DualParams dual;
  OptimParams optim;
  std::string format;  // "" = from the output name
};

ConvertOptions convert_options_from(const Args& a);
// read -> classify -> dual -> star test -> optimise -> write; returns the summary.
Json run_convert(const std::string& in, const std::string& out, const ConvertOptions& o);
void print_convert_summary(const Json& j);

}  // namespace polydual::cli
