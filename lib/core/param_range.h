// Range checks of parameters structs (their validate()): the message names the
// field, its unit and the allowed interval, so a command can pass it on as is.
#pragma once
#include <charconv>
#include <string>

#include "core/error.h"

namespace polydual {

// The shortest decimal that reads back as x ("0.001", "180", "nan").
inline std::string format_param(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

struct ParamRange {
  double lo, hi;
  bool lo_open = false, hi_open = false;  // excluded ends
  bool contains(double x) const {  // false for NaN
    return (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
  }
  std::string str() const {
    return std::string(lo_open ? "(" : "[") + format_param(lo) + ", " + format_param(hi) + (hi_open ? ")" : "]");
  }
};

// Throws UsageError "<field> (<unit>) must be in <range>, got <value>" unless
// the range contains value.
inline void check_param(const char* field, const char* unit, const ParamRange& range, double value) {
  if (range.contains(value)) return;
  throw UsageError(std::string(field) + " (" + unit + ") must be in " + range.str() + ", got " + format_param(value));
}

}  // namespace polydual
