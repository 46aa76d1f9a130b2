// lib/core on its own: the JSON writer's output pinned byte for byte (key
// order, numbers, escaping, nesting) and the stable radix sort that classify
// and the dual rely on (stability, key widths, agreement with std::stable_sort).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <clocale>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <locale>
#include <random>
#include <string>
#include <vector>

#include "core/json.h"
#include "core/radix_sort.h"

using namespace polydual;

// ---- JSON

TEST(Json, KeysInInsertionOrderAndReplacedInPlace) {
  Json j = Json::object();
  j.set("zeta", 1);
  j.set("alpha", 2);
  j.set("mid", 3);
  EXPECT_EQ(j.dump(0), R"({"zeta":1,"alpha":2,"mid":3})");
  j.set("zeta", "again");  // replaced where it was, not moved to the end
  EXPECT_EQ(j.dump(0), R"({"zeta":"again","alpha":2,"mid":3})");
}

TEST(Json, IndentedLayoutIsPinned) {
  Json inner = Json::object();
  inner.set("a", Json::array());
  inner.set("b", Json::object());
  Json arr = Json::array();
  arr.push(1);
  arr.push(inner);
  arr.push(nullptr);
  arr.push(true);
  arr.push(false);
  Json j = Json::object();
  j.set("list", arr);
  j.set("s", "x");
  EXPECT_EQ(j.dump(),
            "{\n"
            "  \"list\": [\n"
            "    1,\n"
            "    {\n"
            "      \"a\": [],\n"
            "      \"b\": {}\n"
            "    },\n"
            "    null,\n"
            "    true,\n"
            "    false\n"
            "  ],\n"
            "  \"s\": \"x\"\n"
            "}");
  EXPECT_EQ(j.dump(0), R"({"list":[1,{"a":[],"b":{}},null,true,false],"s":"x"})");
  EXPECT_EQ(Json().dump(), "null");
  EXPECT_EQ(Json::array().dump(), "[]");
  EXPECT_EQ(Json::object().dump(), "{}");
}

TEST(Json, DeeplyNestedArraysAndObjects) {
  Json j = Json::array();
  for (int depth = 0; depth < 50; ++depth) {
    Json o = Json::object();
    o.set("d", depth);
    o.set("in", j);
    Json a = Json::array();
    a.push(o);
    j = a;
  }
  std::string expect = "[]";
  for (int depth = 0; depth < 50; ++depth) expect = "[{\"d\":" + std::to_string(depth) + ",\"in\":" + expect + "}]";
  EXPECT_EQ(j.dump(0), expect);
}

TEST(Json, IntegersAreExact) {
  EXPECT_EQ(Json(0).dump(), "0");
  EXPECT_EQ(Json(-7).dump(), "-7");
  EXPECT_EQ(Json(std::numeric_limits<long long>::min()).dump(), "-9223372036854775808");
  EXPECT_EQ(Json(std::numeric_limits<long long>::max()).dump(), "9223372036854775807");
  EXPECT_EQ(Json(std::numeric_limits<unsigned long long>::max()).dump(), "18446744073709551615");
  EXPECT_EQ(Json((1ull << 53) + 1).dump(), "9007199254740993");  // not representable as a double
  EXPECT_EQ(Json(std::size_t(4000000000u)).dump(), "4000000000");
  EXPECT_EQ(Json(4294967295u).dump(), "4294967295");
}

TEST(Json, DoublesArePinned) {
  EXPECT_EQ(Json(2.0).dump(), "2");  // integral values below 1e15 as integers
  EXPECT_EQ(Json(-3.0).dump(), "-3");
  EXPECT_EQ(Json(-0.0).dump(), "-0");
  EXPECT_EQ(Json(0.0).dump(), "0");
  EXPECT_EQ(Json(0.1).dump(), "0.10000000000000001");  // 17 significant digits
  EXPECT_EQ(Json(1e15).dump(), "1000000000000000");
  EXPECT_EQ(Json(1e300).dump(), "1.0000000000000001e+300");
  EXPECT_EQ(Json(5e-324).dump(), "4.9406564584124654e-324");
  EXPECT_EQ(Json(std::numeric_limits<double>::quiet_NaN()).dump(), "null");
  EXPECT_EQ(Json(std::numeric_limits<double>::infinity()).dump(), "null");
  EXPECT_EQ(Json(-std::numeric_limits<double>::infinity()).dump(), "null");
}

TEST(Json, DoublesRoundTripExactly) {
  // Random bit patterns (every exponent, subnormals included) and the edges.
  std::mt19937_64 rng(42);
  std::vector<double> values{0.0, -0.0, 1.0, 0.1, 1.0 / 3, std::numeric_limits<double>::max(),
                             std::numeric_limits<double>::min(), std::numeric_limits<double>::denorm_min(),
                             -std::numeric_limits<double>::max(), 999999999999999.0, 1e15 + 1, 123456789.125};
  while (values.size() < 20000) {
    const double d = std::bit_cast<double>(rng());
    if (std::isfinite(d)) values.push_back(d);
  }
  for (double d : values) {
    const std::string s = Json(d).dump();
    char* end = nullptr;
    const double back = std::strtod(s.c_str(), &end);
    ASSERT_EQ(*end, '\0') << s;
    ASSERT_EQ(std::bit_cast<std::uint64_t>(back), std::bit_cast<std::uint64_t>(d)) << s;
  }
}

namespace {
// Decimal comma and digit grouping, as a German locale has (built here, so the
// test needs no installed locale).
struct CommaNumpunct : std::numpunct<char> {
  char do_decimal_point() const override { return ','; }
  char do_thousands_sep() const override { return '.'; }
  std::string do_grouping() const override { return "\3"; }
};
}  // namespace

TEST(Json, NumbersIgnoreTheLocale) {
  const std::locale before = std::locale::global(std::locale(std::locale::classic(), new CommaNumpunct));
  const std::string cxx = Json(0.5).dump() + " " + Json(1234567).dump() + " " + Json(1234567.0).dump() + " " +
                          Json(std::uint64_t(9876543210)).dump();
  std::locale::global(before);
  EXPECT_EQ(cxx, "0.5 1234567 1234567 9876543210");
  // printf's decimal point follows the C locale; the writer must not. (Where
  // no German locale is installed, as on a bare Debian, this checks the C
  // locale only; the C++ part above is checked everywhere.)
  std::setlocale(LC_NUMERIC, "de_DE.UTF-8");
  const std::string c = Json(0.25).dump() + " " + Json(1e-7).dump();
  std::setlocale(LC_NUMERIC, "C");
  EXPECT_EQ(c, "0.25 9.9999999999999995e-08");
}

TEST(Json, StringsAreEscaped) {
  EXPECT_EQ(Json("plain").dump(), "\"plain\"");
  EXPECT_EQ(Json("a\"b\\c/d").dump(), R"("a\"b\\c/d")");
  EXPECT_EQ(Json("l1\nl2\tt\rr").dump(), R"("l1\nl2\tt\rr")");
  std::string controls;
  for (char c = 1; c < 0x20; ++c)
    if (c != '\n' && c != '\t' && c != '\r') controls += c;
  std::string expect = "\"";
  for (char c : controls) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "\\u%04x", unsigned(c));
    expect += buf;
  }
  expect += "\"";
  EXPECT_EQ(Json(controls).dump(), expect);
  EXPECT_EQ(Json(std::string("nul\0byte", 8)).dump(), R"("nul\u0000byte")");
  EXPECT_EQ(Json("\x7f").dump(), "\"\x7f\"");  // DEL is not a control character in JSON
  EXPECT_EQ(Json("\xc3\xa9t\xc3\xa9").dump(), "\"\xc3\xa9t\xc3\xa9\"");  // UTF-8 kept as is
  // Keys are escaped the same way.
  Json o = Json::object();
  o.set("k\"\n", 1);
  EXPECT_EQ(o.dump(0), R"({"k\"\n":1})");
}

TEST(Json, FindAndAt) {
  Json j = Json::object();
  j.set("a", 1);
  Json inner = Json::object();
  inner.set("b", "x");
  j.set("inner", inner);
  ASSERT_NE(j.find("a"), nullptr);
  EXPECT_EQ(j.find("a")->dump(), "1");
  EXPECT_EQ(j.find("missing"), nullptr);
  EXPECT_EQ(j.find("inner")->find("b")->dump(), "\"x\"");
  EXPECT_EQ(j.find("a")->find("a"), nullptr);  // not an object
  *j.find("a") = Json(2.5);                    // find gives the stored value
  EXPECT_EQ(j.dump(0), R"({"a":2.5,"inner":{"b":"x"}})");
  const Json& cj = j;
  EXPECT_EQ(cj.find("inner")->find("b")->dump(), "\"x\"");
  EXPECT_EQ(cj.find("nope"), nullptr);
  Json a = Json::array();
  a.push("first");
  a.push(Json::object());
  EXPECT_EQ(a.find("first"), nullptr);  // arrays have no keys
  EXPECT_EQ(a.at(0).dump(), "\"first\"");
  a.at(1).set("k", true);
  EXPECT_EQ(a.dump(0), R"(["first",{"k":true}])");
  EXPECT_THROW(a.at(2), std::out_of_range);
}

TEST(Json, SetAndPushTurnAValueIntoAnObjectOrArray) {
  Json j = 5;
  j.set("k", 1);
  EXPECT_EQ(j.dump(0), R"({"k":1})");
  Json a = "s";
  a.push(1);
  EXPECT_EQ(a.dump(0), "[1]");
}

// ---- radix sort

namespace {

struct Rec {
  std::uint64_t key;
  std::uint32_t index;  // position before sorting: the payload that shows stability
};

std::vector<Rec> random_records(std::size_t n, int key_bits, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Rec> v(n);
  const std::uint64_t mask = key_bits >= 64 ? ~0ull : (1ull << key_bits) - 1;
  for (std::size_t i = 0; i < n; ++i) v[i] = {rng() & mask, std::uint32_t(i)};
  return v;
}

void expect_same_as_stable_sort(std::vector<Rec> v, int key_bits) {
  std::vector<Rec> ref = v;
  std::stable_sort(ref.begin(), ref.end(), [](const Rec& a, const Rec& b) { return a.key < b.key; });
  radix_sort_by_key(v, [](const Rec& r) { return r.key; }, key_bits);
  ASSERT_EQ(v.size(), ref.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    ASSERT_EQ(v[i].key, ref[i].key) << "at " << i << ", " << key_bits << " bits";
    ASSERT_EQ(v[i].index, ref[i].index) << "at " << i << ", " << key_bits << " bits";
  }
}

}  // namespace

TEST(RadixSort, StableOnManyEqualKeys) {
  // 4 distinct keys among 20000 records: equal keys keep their input order.
  std::vector<Rec> v = random_records(20000, 2, 1);
  radix_sort_by_key(v, [](const Rec& r) { return r.key; }, 2);
  for (std::size_t i = 1; i < v.size(); ++i) {
    ASSERT_LE(v[i - 1].key, v[i].key);
    if (v[i - 1].key == v[i].key) ASSERT_LT(v[i - 1].index, v[i].index) << "at " << i;
  }
  EXPECT_EQ(v.front().key, 0u);
  EXPECT_EQ(v.back().key, 3u);
}

TEST(RadixSort, EveryKeyWidthAgreesWithStableSort) {
  // Widths that are and are not multiples of the 8-bit digit, up to 64; small
  // and large inputs; keys drawn from a narrow range too (many ties, digits
  // that are the same for all keys and so skipped).
  for (int bits : {1, 7, 8, 9, 16, 20, 24, 31, 32, 33, 40, 48, 56, 63, 64}) {
    SCOPED_TRACE(bits);
    for (std::size_t n : {2u, 3u, 255u, 256u, 257u, 5000u}) {
      expect_same_as_stable_sort(random_records(n, bits, 100 + bits + n), bits);
      std::vector<Rec> narrow = random_records(n, std::min(bits, 3), 7 * n + bits);
      for (Rec& r : narrow) r.key <<= (bits - std::min(bits, 3));  // only the top digit varies
      expect_same_as_stable_sort(narrow, bits);
    }
  }
}

TEST(RadixSort, ThirtyTwoBitKeysFromA32BitKeyFunction) {
  // The key function may return a 32-bit type (as classify's does).
  std::vector<Rec> v = random_records(3000, 32, 9);
  std::vector<Rec> ref = v;
  std::stable_sort(ref.begin(), ref.end(), [](const Rec& a, const Rec& b) { return a.key < b.key; });
  radix_sort_by_key(v, [](const Rec& r) { return std::uint32_t(r.key); }, 32);
  for (std::size_t i = 0; i < v.size(); ++i) ASSERT_EQ(v[i].index, ref[i].index);
}

TEST(RadixSort, AlreadySortedReversedAndConstantInputs) {
  std::vector<Rec> sorted(1000), reversed(1000), constant(1000);
  for (std::uint32_t i = 0; i < 1000; ++i) {
    sorted[i] = {i, i};
    reversed[i] = {999u - i, i};
    constant[i] = {0xabcdefu, i};
  }
  expect_same_as_stable_sort(sorted, 16);
  expect_same_as_stable_sort(reversed, 16);
  expect_same_as_stable_sort(constant, 24);  // every pass skipped: input order kept
}

TEST(RadixSort, EmptyAndOneElement) {
  std::vector<Rec> empty;
  radix_sort_by_key(empty, [](const Rec& r) { return r.key; }, 32);
  EXPECT_TRUE(empty.empty());
  std::vector<Rec> one{{12345, 0}};
  radix_sort_by_key(one, [](const Rec& r) { return r.key; }, 32);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].key, 12345u);
  EXPECT_EQ(one[0].index, 0u);
}

TEST(RadixSort, RandomDataAgreesWithStableSort) {
  std::mt19937_64 rng(2024);
  for (int round = 0; round < 40; ++round) {
    const std::size_t n = rng() % 20000;
    const int bits = 1 + int(rng() % 64);
    SCOPED_TRACE("n " + std::to_string(n) + " bits " + std::to_string(bits));
    expect_same_as_stable_sort(random_records(n, bits, rng()), bits);
  }
}
