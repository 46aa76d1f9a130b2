// Errors that lib/ returns to its callers (lib/ never prints or exits).
#pragma once
#include <stdexcept>
#include <string>

namespace polydual {

// Bad input: names the source (file or "<memory>") and the place in it
// ("line 12", "element 7", "byte 4096", "tet 31"), then what is wrong.
class InputError : public std::runtime_error {
 public:
  InputError(std::string source, std::string place, const std::string& what)
      : std::runtime_error(format(source, place, what)), source_(std::move(source)),
        place_(std::move(place)) {}
  const std::string& source() const { return source_; }
  const std::string& place() const { return place_; }

 private:
  static std::string format(const std::string& s, const std::string& p, const std::string& w) {
    std::string m = s.empty() ? std::string("<input>") : s;
    if (!p.empty()) m += ": " + p;
    return m + ": " + w;
  }
  std::string source_, place_;
};

// Bad usage of the library (wrong option values, unknown names).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Memory ran out in a named stage of the work ("dual", "optimize"): a
// std::bad_alloc rethrown with where it happened and how much the process
// held then, so the user knows what to shrink.
class OutOfMemory : public std::runtime_error {
 public:
  OutOfMemory(const std::string& stage, double peak_rss_mb)
      : std::runtime_error("out of memory in stage '" + stage + "' (peak resident memory " +
                           std::to_string(long(peak_rss_mb)) + " MB)") {}
};

}  // namespace polydual
