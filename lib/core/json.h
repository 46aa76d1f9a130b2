// A minimal JSON writer (objects, arrays, numbers, strings) with deterministic
// output: keys appear in insertion order, doubles with 17 significant digits.
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
  Json(int i) : v_(static_cast<double>(i)), integral_(true) {}
  Json(long i) : v_(static_cast<double>(i)), integral_(true) {}
  Json(long long i) : v_(static_cast<double>(i)), integral_(true) {}
  Json(unsigned i) : v_(static_cast<double>(i)), integral_(true) {}
  Json(unsigned long i) : v_(static_cast<double>(i)), integral_(true) {}
  Json(unsigned long long i) : v_(static_cast<double>(i)), integral_(true) {}
  Json(double d) : v_(d) {}
  Json(const char* s) : v_(std::string(s)) {}
  Json(std::string s) : v_(std::move(s)) {}

  static Json object() { Json j; j.v_ = Object{}; return j; }
  static Json array() { Json j; j.v_ = Array{}; return j; }

  // Object: set (or replace) a key, keeping first-insertion order.
  Json& set(const std::string& key, Json value);
  // Array: append.
  Json& push(Json value);
  Json* find(const std::string& key);
  // Object member or nullptr (also for a non-object).
  const Json* find(const std::string& key) const;
  // Array element i (the array must have it).
  Json& at(std::size_t i) { return std::get<Array>(v_).at(i); }
  const Json& at(std::size_t i) const { return std::get<Array>(v_).at(i); }

  std::string dump(int indent = 2) const;

 private:
  using Object = std::vector<std::pair<std::string, Json>>;
  using Array = std::vector<Json>;
  void write(std::ostringstream& os, int indent, int depth) const;
  std::variant<std::nullptr_t, bool, double, std::string, Object, Array> v_;
  bool integral_ = false;
};

}  // namespace polydual
