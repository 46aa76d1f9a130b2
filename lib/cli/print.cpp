#include "cli/print.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>

namespace polydual::cli {

void print_warnings(const std::vector<std::string>& warnings, bool quiet) {
  if (quiet) return;
  for (const std::string& w : warnings) std::fprintf(stderr, "polydual: warning: %s\n", w.c_str());
}

void print_json(const Json& j) { std::cout << j.dump() << "\n"; }

void print_defects(const std::string& command, const char* level, const std::string& headline,
                   const std::vector<Defect>& defects) {
  std::cout.flush();  // the summary first when both go to one terminal
  std::fprintf(stderr, "polydual %s: %s: %s\n", command.c_str(), level, headline.c_str());
  for (const Defect& d : defects) std::fprintf(stderr, "  %s\n", defect_line(d).c_str());
}

void print_convert_summary(const Json& j) {
  auto val = [&](const char* k) { return j.find(k) ? j.find(k)->dump(0) : std::string("?"); };
  const Json* out = j.find("output");
  std::printf("%s -> %s\n", val("input").c_str(), out && out->find("path") ? out->find("path")->dump(0).c_str() : "?");
  if (const Json* mixed = j.find("input_cells"))  // a mixed mesh: its cells per type
    std::printf("  mixed mesh (%s) -> cells %s, faces %s, points %s\n", mixed->dump(0).c_str(), val("cells").c_str(),
                val("faces").c_str(), val("points").c_str());
  else
    std::printf("  tets %s -> cells %s, faces %s, points %s\n", val("tets").c_str(), val("cells").c_str(),
                val("faces").c_str(), val("points").c_str());
  std::printf("  invalid cells (exact star test): before %s, after %s; closed cells %s; slit cells %s\n",
              val("invalid_before").c_str(), val("invalid_after").c_str(), val("closed_cells").c_str(),
              val("slit_cells").c_str());
  if (const Json* d = j.find("defects"); d && d->dump(0) != "[]")
    std::printf("  NOT SOUND: the validation found defects (listed on stderr)\n");
  std::printf("  seconds %s\n", val("seconds").c_str());
}

namespace {
constexpr double kProgressDelaySeconds = 2.0;  // shorter stages print nothing
double progress_delay() {
  const char* env = std::getenv("POLYDUAL_PROGRESS_DELAY");
  char* end = nullptr;
  const double v = env ? std::strtod(env, &end) : kProgressDelaySeconds;
  return env && end != env && v >= 0 ? v : kProgressDelaySeconds;
}
}  // namespace

ProgressPrinter::ProgressPrinter(bool quiet)
    : quiet_(quiet), tty_(::isatty(STDERR_FILENO) == 1), delay_(progress_delay()) {}

ProgressPrinter::~ProgressPrinter() { end_line(); }

ProgressFn ProgressPrinter::progress() {
  return [this](const ProgressEvent& e) { show(e); };
}

ConvertHooks ProgressPrinter::hooks() {
  ConvertHooks h;
  h.progress = progress();
  h.stage_done = [this](const StageRecord&) { end_line(); };
  return h;
}

void ProgressPrinter::end_line() {
  if (live_) std::fputc('\n', stderr);
  live_ = false;
}

void ProgressPrinter::show(const ProgressEvent& e) {
  if (quiet_ || e.seconds < delay_) return;
  char eta[48] = "";
  if (e.max_steps > e.step && e.step > 0)
    std::snprintf(eta, sizeof eta, ", ETA <= %.0f s", e.seconds / e.step * (e.max_steps - e.step));
  std::fprintf(stderr, "%spolydual: %s %d/%d: %s, %.1f s%s%s", tty_ ? "\r" : "", e.stage, e.step, e.max_steps,
               e.detail.c_str(), e.seconds, eta, tty_ ? "\033[K" : "\n");
  std::fflush(stderr);
  live_ = tty_;
}

}  // namespace polydual::cli
