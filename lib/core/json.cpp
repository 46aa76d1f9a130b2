#include "core/json.h"

#include <charconv>
#include <cstdio>
#include <locale>

namespace polydual {

Json& Json::set(const std::string& key, Json value) {
  if (!std::holds_alternative<Object>(v_)) v_ = Object{};
  auto& o = std::get<Object>(v_);
  for (auto& kv : o)
    if (kv.first == key) { kv.second = std::move(value); return kv.second; }
  o.emplace_back(key, std::move(value));
  return o.back().second;
}

Json& Json::push(Json value) {
  if (!std::holds_alternative<Array>(v_)) v_ = Array{};
  auto& a = std::get<Array>(v_);
  a.push_back(std::move(value));
  return a.back();
}

Json* Json::find(const std::string& key) {
  return const_cast<Json*>(static_cast<const Json&>(*this).find(key));
}

const Json* Json::find(const std::string& key) const {
  if (!std::holds_alternative<Object>(v_)) return nullptr;
  for (const auto& kv : std::get<Object>(v_))
    if (kv.first == key) return &kv.second;
  return nullptr;
}

static void write_string(std::ostringstream& os, const std::string& s) {
  os << '"';
  for (unsigned char c : s) {
    switch (c) {
      case '"': os << "\\\""; break;
      case '\\': os << "\\\\"; break;
      case '\n': os << "\\n"; break;
      case '\t': os << "\\t"; break;
      case '\r': os << "\\r"; break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          os << buf;
        } else {
          os << c;
        }
    }
  }
  os << '"';
}

static void write_double(std::ostringstream& os, double d) {
  if (!std::isfinite(d)) {
    os << "null";
  } else if (d == std::floor(d) && std::fabs(d) < 1e15) {
    if (std::signbit(d)) os << '-';  // keeps -0 (the cast below would drop its sign)
    os << static_cast<long long>(std::fabs(d));
  } else {
    char buf[32];
    const auto res = std::to_chars(buf, buf + sizeof buf, d, std::chars_format::general, 17);
    os.write(buf, res.ptr - buf);
  }
}

void Json::write(std::ostringstream& os, int indent, int depth) const {
  auto nl = [&](int d) {
    if (indent <= 0) return;
    os << '\n' << std::string(static_cast<std::size_t>(indent * d), ' ');
  };
  if (std::holds_alternative<std::nullptr_t>(v_)) {
    os << "null";
  } else if (auto b = std::get_if<bool>(&v_)) {
    os << (*b ? "true" : "false");
  } else if (auto d = std::get_if<double>(&v_)) {
    write_double(os, *d);
  } else if (auto i = std::get_if<std::int64_t>(&v_)) {
    os << *i;
  } else if (auto u = std::get_if<std::uint64_t>(&v_)) {
    os << *u;
  } else if (auto s = std::get_if<std::string>(&v_)) {
    write_string(os, *s);
  } else if (auto o = std::get_if<Object>(&v_)) {
    os << '{';
    bool first = true;
    for (const auto& kv : *o) {
      if (!first) os << ',';
      first = false;
      nl(depth + 1);
      write_string(os, kv.first);
      os << (indent > 0 ? ": " : ":");
      kv.second.write(os, indent, depth + 1);
    }
    if (!o->empty()) nl(depth);
    os << '}';
  } else if (auto a = std::get_if<Array>(&v_)) {
    os << '[';
    bool first = true;
    for (const auto& e : *a) {
      if (!first) os << ',';
      first = false;
      nl(depth + 1);
      e.write(os, indent, depth + 1);
    }
    if (!a->empty()) nl(depth);
    os << ']';
  }
}

std::string Json::dump(int indent) const {
  std::ostringstream os;
  os.imbue(std::locale::classic());  // no digit grouping from a global locale
  write(os, indent, 0);
  return os.str();
}

}  // namespace polydual
