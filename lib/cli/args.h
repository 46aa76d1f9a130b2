// Command-line parsing for the polydual subcommands: every option is declared
// (name, takes a value or not, help); anything else is a usage error (exit 2).
#pragma once
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace polydual::cli {

struct OptionSpec {
  std::string name;       // "--tets"
  std::string value;      // value placeholder ("N"); empty for a flag
  std::string help;
};

struct CommandSpec {
  std::string name, synopsis, description;
  int min_positional = 0, max_positional = 0;
  std::vector<OptionSpec> options;
};

class UsageFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Args {
  std::vector<std::string> positional;
  std::map<std::string, std::string> values;
  bool help = false;
  bool has(const std::string& name) const { return values.count(name) > 0; }
  std::string get(const std::string& name, const std::string& fallback = "") const {
    auto it = values.find(name);
    return it == values.end() ? fallback : it->second;
  }
  double get_double(const std::string& name, double fallback) const;
  long long get_int(const std::string& name, long long fallback) const;
};

Args parse_args(const CommandSpec& spec, int argc, char** argv);
std::string help_text(const CommandSpec& spec);

}  // namespace polydual::cli
