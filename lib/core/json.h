// A minimal JSON writer (objects, arrays, numbers, strings) with deterministic
// output: keys appear in insertion order; integers exactly; a double with an
// integral value below 1e15 in magnitude as an integer ("2", "-0"), any other
// finite double with 17 significant digits ("%.17g" in the C locale, whatever
// the process's locale), so that reading it back gives the same double; NaN
// and infinities as null. Strings are escaped as RFC 8259 requires: quote,
// backslash, \n \t \r, other control characters as \u00xx; other bytes
// (UTF-8) as they are.
#pragma once
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace polydual {

class Json {
 public:
  Json() : v_(nullptr) {}
  Json(std::nullptr_t) : v_(nullptr) {}
  Json(bool b) : v_(b) {}
  // Integers are kept exactly (64-bit), whatever their size.
  Json(int i) : v_(std::int64_t(i)) {}
  Json(long i) : v_(std::int64_t(i)) {}
  Json(long long i) : v_(std::int64_t(i)) {}
  Json(unsigned i) : v_(std::uint64_t(i)) {}
  Json(unsigned long i) : v_(std::uint64_t(i)) {}
  Json(unsigned long long i) : v_(std::uint64_t(i)) {}
  Json(double d) : v_(d) {}
  Json(const char* s) : v_(std::string(s)) {}
  Json(std::string s) : v_(std::move(s)) {}

  static Json object() { Json j; j.v_ = Object{}; return j; }
  static Json array() { Json j; j.v_ = Array{}; return j; }

  // Object: set (or replace) a key, keeping first-insertion order.
  Json& set(const std::string& key, Json value);
  // Array: append.
  Json& push(Json value);
  // Object: the value of a key, or null when absent or not an object.
  Json* find(const std::string& key);
  const Json* find(const std::string& key) const;
  // Array element i (the array must have it).
  Json& at(std::size_t i) { return std::get<Array>(v_).at(i); }
  const Json& at(std::size_t i) const { return std::get<Array>(v_).at(i); }

  std::string dump(int indent = 2) const;

 private:
  using Object = std::vector<std::pair<std::string, Json>>;
  using Array = std::vector<Json>;
  void write(std::ostringstream& os, int indent, int depth) const;
  std::variant<std::nullptr_t, bool, double, std::int64_t, std::uint64_t, std::string, Object, Array> v_;
};

}  // namespace polydual
