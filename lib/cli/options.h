// The command's options, declared once (lib/cli/options.cpp): name, value
// type and range, default (read from the params structs, so it is written in
// one place), help, and how the value lands in Settings. A subcommand lists
// the names it accepts; parsing, range checks and help text are shared.
#pragma once
#include <stdexcept>
#include <string>
#include <vector>

#include "io/write_poly_mesh.h"
#include "pipeline/params.h"

namespace polydual::cli {

// Everything the flags of any subcommand can set.
struct Settings {
  PipelineParams params;
  PolyWriteOptions write;           // --vtu-encoding, --zlib, --force
  std::vector<std::string> positional;
  std::string out;                  // -o
  std::string format;               // --format ("" = from the output name)
  std::string primal;               // --primal
  std::string out_dir = "polydual-demo";  // --out (demo)
  std::string domains = "cube,twomat,fichera,fracture,network,fins,layers,dfn";
  long long tets = 0;               // --tets (0 = the command's default)
  int threads = 0;                  // --threads (0 = all cores)
  bool json = false, quiet = false, help = false;
};

enum class OptionKind { Flag, Int, Real, Choice, Text };

struct OptionDef {
  const char* name;     // "--feature-angle"
  OptionKind kind;
  const char* value;    // placeholder in the help ("DEG"); choices "a|b" for Choice
  double lo, hi;        // accepted range (Int, Real)
  const char* help;
  std::string (*default_text)(const Settings& defaults);  // nullptr: no default shown
  void (*apply)(Settings& s, const std::string& value);
};

// One subcommand: its synopsis, description, positional count and options
// (names from the table; a "=VALUE" suffix overrides the shown default).
struct CommandSpec {
  std::string name, synopsis, description;
  int min_positional = 0, max_positional = 0;
  std::vector<std::string> options;
};

class UsageFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

const OptionDef& option(const std::string& name);  // throws std::logic_error if not declared

// Parses argv (after the subcommand) into `defaults`; throws UsageFailure for
// an unknown option, a missing or malformed value, a value out of range, or a
// wrong number of positional arguments (unless --help).
Settings parse_command_line(const CommandSpec& spec, int argc, char** argv, Settings defaults = {});
std::string help_text(const CommandSpec& spec, const Settings& defaults = {});

}  // namespace polydual::cli
