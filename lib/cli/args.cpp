#include "cli/args.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace polydual::cli {

Args parse_args(const CommandSpec& spec, int argc, char** argv) {
  Args a;
  for (int i = 0; i < argc; ++i) {
    std::string s = argv[i];
    if (s == "-h" || s == "--help") { a.help = true; continue; }
    if (s.size() > 1 && s[0] == '-' && !(s.size() > 1 && (std::isdigit(static_cast<unsigned char>(s[1])) || s[1] == '.'))) {
      std::string name = s, inline_value;
      bool has_inline = false;
      if (auto eq = s.find('='); eq != std::string::npos) {
        name = s.substr(0, eq);
        inline_value = s.substr(eq + 1);
        has_inline = true;
      }
      const OptionSpec* o = nullptr;
      for (const auto& op : spec.options)
        if (op.name == name) o = &op;
      if (!o) throw UsageFailure("unknown option '" + name + "' for '" + spec.name + "' (see polydual " + spec.name + " --help)");
      if (o->value.empty()) {
        if (has_inline) throw UsageFailure("option " + name + " takes no value");
        a.values[name] = "1";
      } else if (has_inline) {
        a.values[name] = inline_value;
      } else {
        if (i + 1 >= argc) throw UsageFailure("option " + name + " needs a value (" + o->value + ")");
        a.values[name] = argv[++i];
      }
      continue;
    }
    a.positional.push_back(s);
  }
  if (!a.help) {
    if (int(a.positional.size()) < spec.min_positional)
      throw UsageFailure("missing argument for '" + spec.name + "': usage: polydual " + spec.synopsis);
    if (int(a.positional.size()) > spec.max_positional)
      throw UsageFailure("unexpected argument '" + a.positional[spec.max_positional] + "' for '" + spec.name + "'");
  }
  return a;
}

double Args::get_double(const std::string& name, double fallback) const {
  if (!has(name)) return fallback;
  const std::string& s = values.at(name);
  char* end = nullptr;
  errno = 0;
  double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end || errno || !std::isfinite(v)) throw UsageFailure("option " + name + ": '" + s + "' is not a number");
  return v;
}

long long Args::get_int(const std::string& name, long long fallback) const {
  if (!has(name)) return fallback;
  const std::string& s = values.at(name);
  char* end = nullptr;
  errno = 0;
  long long v = std::strtoll(s.c_str(), &end, 10);
  if (s.empty() || *end || errno) throw UsageFailure("option " + name + ": '" + s + "' is not an integer");
  return v;
}

std::string help_text(const CommandSpec& spec) {
  std::ostringstream os;
  os << "usage: polydual " << spec.synopsis << "\n\n" << spec.description << "\n";
  if (!spec.options.empty()) {
    os << "\noptions:\n";
    for (const auto& o : spec.options) {
      std::string lhs = "  " + o.name + (o.value.empty() ? "" : " " + o.value);
      os << lhs << std::string(lhs.size() < 28 ? 28 - lhs.size() : 1, ' ') << o.help << "\n";
    }
    os << "  -h, --help                  this help\n";
  }
  return os.str();
}

}  // namespace polydual::cli
