// shortest_chars against std::to_chars (the exports' contract is std::to_chars' text): the same
// characters for a spread of every float (each 1,021st bit pattern, all signs, subnormals, NaNs
// and infinities included), for every float of the ranges where the layout changes (whole numbers
// where std::to_chars writes exact digits, the fixed/scientific turning points), and for random
// doubles, both random bit patterns and values of the sizes the exports hold. (Every one of the
// 2^32 floats was compared once when this was written; it takes half an hour.)
#include "geometry/shortest_number.hpp"

#include <doctest/doctest.h>

#include <charconv>
#include <cmath>
#include <cstring>
#include <random>
#include <string>

using namespace canopy;

namespace {

template <typename T>
std::string theirs(T v) {
  char buf[64];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

template <typename T>
std::string ours(T v) {
  char buf[64];
  return std::string(buf, shortest_chars(buf, v));
}

float float_of(std::uint32_t bits) {
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

/// Counts the values of [first, last) (bit patterns, stepping by `step`) that differ, and shows
/// the first.
std::size_t float_mismatches(std::uint64_t first, std::uint64_t last, std::uint64_t step) {
  std::size_t bad = 0;
  for (std::uint64_t b = first; b < last; b += step) {
    const float f = float_of(static_cast<std::uint32_t>(b));
    if (ours(f) != theirs(f) && bad++ == 0)
      CHECK_MESSAGE(false, "float bits " << b << ": " << ours(f) << " vs " << theirs(f));
  }
  return bad;
}

}  // namespace

TEST_CASE("shortest_chars writes what std::to_chars writes: floats") {
  CHECK(float_mismatches(0, std::uint64_t(1) << 32, 1021) == 0);
  // Around the whole numbers where the fixed form takes exact digits (2^24 and up) and the
  // points where fixed and scientific are the same length (1e-5, 1e+5 .. 1e+14).
  for (const float at :
       {1e-5f, 1e-4f, 1e5f, 1e6f, 1e7f, 16777216.0f, 1e8f, 1e9f, 1e10f, 1e11f, 1e12f, 1e13f, 1e14f, 1e15f}) {
    std::uint32_t bits;
    std::memcpy(&bits, &at, 4);
    CHECK(float_mismatches(bits - 20000, bits + 20000, 1) == 0);
    CHECK(float_mismatches((bits - 20000) | 0x80000000u, (bits + 20000) | 0x80000000u, 1) == 0);
  }
  for (const float v :
       {0.0f, -0.0f, 1.0f, -1.0f, 0.1f, 3.0e38f, 1e-45f, 1.17549435e-38f, INFINITY, -INFINITY, NAN, -NAN})
    CHECK(ours(v) == theirs(v));
}

TEST_CASE("shortest_chars writes what std::to_chars writes: doubles") {
  std::mt19937_64 rng(7);
  std::size_t bad = 0;
  for (int i = 0; i < 400000; ++i) {
    double d;
    if (i % 3 == 0) {
      const std::uint64_t u = rng();
      std::memcpy(&d, &u, 8);
    } else if (i % 3 == 1) {  // whole numbers and fractions of every size the fixed form may take
      d = std::ldexp(static_cast<double>(rng() >> 11), static_cast<int>(rng() % 140) - 100);
    } else {  // floats widened, as organs.csv writes lengths and areas
      d = static_cast<double>(std::uniform_real_distribution<float>(-2.0f, 2.0f)(rng));
    }
    if (i % 2) d = -d;
    if (ours(d) != theirs(d) && bad++ == 0) CHECK_MESSAGE(false, ours(d) << " vs " << theirs(d));
  }
  CHECK(bad == 0);
  for (const double v : {0.0, -0.0, 1.0, 1e22, 9.999999999999999e21, 1e21, 123456789012345678.0, 5e-324,
                         1.7976931348623157e308, 0.1, 1e-5, 1e-4, 1e15, 1e16, 1e17, double(INFINITY),
                         -double(INFINITY), double(NAN)})
    CHECK(ours(v) == theirs(v));
}
