// The polydual command (lib/cli): parses options into params, calls the
// library (lib/pipeline), prints.
// Exit codes: 0 success, 1 error (bad input, I/O), 2 bad usage.
#include <cstdio>
#include <cstring>
#include <new>
#include <memory>
#include <string>

#include <tbb/global_control.h>

#include "cli/commands.h"
#include "core/error.h"
#include "core/interrupt.h"

using namespace polydual;
using namespace polydual::cli;

namespace {
struct Command {
  const CommandSpec* spec;
  int (*run)(const Settings&);
};
const Command kCommands[] = {{&kDemo, cmd_demo},       {&kGenerate, cmd_generate}, {&kInfo, cmd_info},
                             {&kConvert, cmd_convert}, {&kCheck, cmd_check},       {&kOptimize, cmd_optimize}};

void usage(std::FILE* f) {
  std::fprintf(f,
               "polydual: polyhedral meshes of non-manifold domains from classified tet meshes\n"
               "usage: polydual COMMAND [options]   (polydual COMMAND --help for details)\n\ncommands:\n");
  for (const auto& c : kCommands) std::fprintf(f, "  %s\n", c.spec->synopsis.c_str());
}
}  // namespace

// After Ctrl-C or SIGTERM a run stops at its next poll point (between output
// chunks, sweeps, rounds) and says so; one that does not poll within this
// time (Gmsh meshing, a blocked system call) is ended by the watchdog, its
// temporaries removed, with the same exit status.
constexpr double kInterruptGraceSeconds = 1.0;

int main(int argc, char** argv) {
  start_interrupt_watchdog(kInterruptGraceSeconds);
  if (argc < 2) { usage(stderr); return 2; }
  const std::string name = argv[1];
  if (name == "-h" || name == "--help" || name == "help") { usage(stdout); return 0; }
  for (const auto& c : kCommands) {
    if (c.spec->name != name) continue;
    try {
      const Settings s = parse_command_line(*c.spec, argc - 2, argv + 2);
      if (s.help) { std::fputs(help_text(*c.spec).c_str(), stdout); return 0; }
      // Outputs do not depend on the thread count (deterministic stages).
      std::unique_ptr<tbb::global_control> threads;
      if (s.threads > 0)
        threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, s.threads);
      return c.run(s);
    } catch (const Interrupted& e) {  // the writers removed their temporaries
      std::fprintf(stderr, "polydual %s: interrupted\n", name.c_str());
      return e.exit_status();
    } catch (const UsageFailure& e) {
      std::fprintf(stderr, "polydual %s: usage error: %s\n", name.c_str(), e.what());
      return 2;
    } catch (const UsageError& e) {
      std::fprintf(stderr, "polydual %s: usage error: %s\n", name.c_str(), e.what());
      return 2;
    } catch (const InputError& e) {
      std::fprintf(stderr, "polydual %s: error: %s\n", name.c_str(), e.what());
      return 1;
    } catch (const std::bad_alloc&) {
      std::fprintf(stderr, "polydual %s: error: out of memory\n", name.c_str());
      return 1;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "polydual %s: error: %s\n", name.c_str(), e.what());
      return 1;
    }
  }
  std::fprintf(stderr, "polydual: unknown command '%s'\n", name.c_str());
  usage(stderr);
  return 2;
}
