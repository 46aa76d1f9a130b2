// Human-readable lines for the summaries the library returns, and the
// warnings of a read (stderr unless --quiet).
#pragma once
#include <string>

#include "core/json.h"
#include "core/progress.h"
#include "pipeline/convert.h"

namespace polydual::cli {

void print_convert_summary(const Json& summary);
// The reader's warnings on stderr, one line each (nothing when quiet).
void print_warnings(const std::vector<std::string>& warnings, bool quiet);
void print_json(const Json& j);  // one object on stdout
// A validation's failed checks on stderr: "polydual COMMAND: LEVEL: HEADLINE"
// then one line per defect (its cells, at most 10, then "and N more").
// Printed even when quiet: they say the output is broken.
void print_defects(const std::string& command, const char* level, const std::string& headline,
                   const std::vector<Defect>& defects);

// Shows the progress of long stages on stderr: only once a stage has run for
// 2 s (POLYDUAL_PROGRESS_DELAY seconds if set), as one live line on a
// terminal and as plain lines otherwise; nothing when quiet.
class ProgressPrinter {
 public:
  explicit ProgressPrinter(bool quiet);
  ~ProgressPrinter();
  ProgressFn progress();
  ConvertHooks hooks();  // progress, and the end of a live line after each stage
  void end_line();

 private:
  void show(const ProgressEvent& e);
  bool quiet_, tty_, live_ = false;
  double delay_;
};

}  // namespace polydual::cli
