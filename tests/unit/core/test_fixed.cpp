// Exact decimals (core/fixed.hpp): the arithmetic of inserted numbers (E - 2,
// Z + lift) is the decimal the user means, rounding is half away from zero,
// to_double() is the double that parsing the text gives, and junk saturates.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>

#include "gcode/core/fixed.hpp"
#include "gcode/core/number.hpp"

using gcode::Fixed;

namespace {

std::string text(Fixed f, int decimals) {
  char b[gcode::kMaxNumberChars];
  return std::string(b, f.format(decimals, b));
}

Fixed dec(std::int64_t mantissa, int decimals) { return Fixed::from_decimal(mantissa, decimals); }

}  // namespace

TEST_CASE("fixed: 5.0348 - 2 is 3.0348, not binary noise", "[fixed]") {
  Fixed e = dec(50348, 4) - Fixed::from_int(2);
  CHECK(e.units() == 3'034'800'000);
  CHECK(text(e, 4) == "3.0348");
  CHECK(text(e, 9) == "3.0348");
  CHECK(e.to_double() == 3.0348);
  CHECK(5.0348 - 2 != 3.0348);  // what the doubles gave (3.0347999999999997)
  // The Slic3r lift of the issue: 8.955 + 0.2.
  Fixed z = dec(8955, 3) + dec(2, 1);
  CHECK(text(z, 3) == "9.155");
  CHECK(z == dec(9155, 3));
  // and back: the return to the paused position is exact.
  CHECK(z - dec(2, 1) == dec(8955, 3));
}

TEST_CASE("fixed: sums carry across the point and through zero", "[fixed]") {
  CHECK(dec(9999, 4) + dec(1, 4) == Fixed::from_int(1));
  CHECK(text(dec(9999, 4) + dec(1, 4), 4) == "1");
  CHECK(text(dec(-1, 4) - dec(9999, 4), 4) == "-1");
  CHECK(text(dec(5, 1) - dec(12, 1), 1) == "-0.7");
  CHECK((dec(-8, 1) + dec(8, 1)).is_zero());
  CHECK(text(dec(-8, 1) + dec(8, 1), 3) == "0");
  // 0.1 + 0.2 is 0.3, ten thousand relative moves of 0.01 are 100.
  CHECK(dec(1, 1) + dec(2, 1) == dec(3, 1));
  Fixed sum;
  for (int i = 0; i < 10000; ++i) sum += dec(1, 2);
  CHECK(sum == Fixed::from_int(100));
  Fixed back = sum;
  for (int i = 0; i < 10000; ++i) back -= dec(1, 2);
  CHECK(back.is_zero());
  CHECK(-dec(25, 1) == dec(-25, 1));
}

TEST_CASE("fixed: negative numbers keep their sign in text", "[fixed]") {
  CHECK(text(dec(-80, 2), 2) == "-0.8");
  CHECK(text(dec(-80, 2), 0) == "-1");  // -0.8 rounded half away from zero
  CHECK(text(dec(-4, 1), 0) == "0");    // never "-0"
  CHECK(text(dec(-1, 4), 3) == "0");
  CHECK(text(dec(-123456, 3), 3) == "-123.456");
  CHECK(dec(-80, 2) < Fixed());
  CHECK(dec(-80, 2) > dec(-81, 2));
}

TEST_CASE("fixed: rounding to fewer decimals is half away from zero, in decimal", "[fixed]") {
  CHECK(dec(30348, 4).scaled(3) == 3035);
  CHECK(dec(30348, 4).scaled(2) == 303);
  CHECK(dec(-25, 1).scaled(0) == -3);
  CHECK(dec(25, 1).scaled(0) == 3);
  CHECK(dec(24999, 4).scaled(0) == 2);
  // 9.155 is 9.1549999... as a double, so a double rounds it down; the
  // decimal it stands for rounds up.
  CHECK(dec(9155, 3).rounded(2) == dec(916, 2));
  CHECK(dec(-9155, 3).rounded(2) == dec(-916, 2));
  CHECK(text(dec(9155, 3), 2) == "9.16");
  CHECK(dec(9155, 3).rounded(9) == dec(9155, 3));
  CHECK(dec(9155, 3).rounded(12) == dec(9155, 3));
  CHECK(dec(9155, 3).rounded(-1) == Fixed::from_int(9));
  CHECK(dec(9155, 3).scaled(12) == dec(9155, 3).units());
}

TEST_CASE("fixed: nine decimals are exact, more are rounded", "[fixed]") {
  CHECK(dec(123456789, 9).units() == 123456789);
  CHECK(text(dec(123456789, 9), 9) == "0.123456789");
  CHECK(text(dec(123456789, 9), 12) == "0.123456789");  // at most nine
  CHECK(dec(123456789012, 12).units() == 123456789);
  CHECK(dec(5, 10).units() == 1);     // 0.0000000005: half away from zero
  CHECK(dec(-5, 10).units() == -1);
  CHECK(dec(4, 10).units() == 0);
  CHECK(dec(1, 40).units() == 0);     // beyond any power of ten kept
  CHECK(dec(7800000, 3) == Fixed::from_int(7800));
}

TEST_CASE("fixed: a negative count of decimals scales up", "[fixed]") {
  // mantissa x 10^-decimals: 5 x 10^2.
  CHECK(dec(5, -2) == Fixed::from_int(500));
  CHECK(dec(-12, -1) == Fixed::from_int(-120));
  CHECK(dec(5, -30).units() == Fixed::kMax);
}

TEST_CASE("fixed: to_double is the double the decimal text parses to", "[fixed][property]") {
  // Every value with up to four decimals in +-500 mm, and some of nine.
  for (std::int64_t m = -5'000'000; m <= 5'000'000; m += 997) {
    Fixed f = dec(m, 4);
    char b[gcode::kMaxNumberChars];
    std::string written(b, f.format(4, b));
    double parsed = 0;
    REQUIRE(gcode::parse_number(written, parsed));
    REQUIRE(f.to_double() == parsed);
    REQUIRE(std::stod(written) == parsed);
  }
  CHECK(dec(123456789, 9).to_double() == 0.123456789);
  CHECK(dec(-987654321987, 9).to_double() == -987.654321987);
}

TEST_CASE("fixed: from_double rounds to 10^-9 and removes the binary noise", "[fixed]") {
  CHECK(Fixed::from_double(5.0348 - 2) == dec(30348, 4));
  CHECK(Fixed::from_double(0.1 + 0.2) == dec(3, 1));
  CHECK(Fixed::from_double(-0.8) == dec(-8, 1));
  CHECK(Fixed::from_double(0.0000000005).units() == 1);
  CHECK(Fixed::from_double(std::nan("")).is_zero());
  CHECK(Fixed::from_double(std::numeric_limits<double>::infinity()).units() == Fixed::kMax);
  CHECK(Fixed::from_double(-std::numeric_limits<double>::infinity()).units() == -Fixed::kMax);
  CHECK(Fixed::from_double(1e300).units() == Fixed::kMax);
}

TEST_CASE("fixed: junk saturates instead of wrapping", "[fixed]") {
  const Fixed top = Fixed::from_units(Fixed::kMax);
  CHECK(Fixed::from_units(std::numeric_limits<std::int64_t>::max()) == top);
  CHECK(Fixed::from_units(std::numeric_limits<std::int64_t>::min()) == -top);
  CHECK(top + top == top);
  CHECK(-top - top == -top);
  CHECK(top - (-top) == top);
  CHECK(Fixed::from_int(std::numeric_limits<std::int64_t>::max() / 10) == top);
  CHECK(Fixed::from_int(-std::numeric_limits<std::int64_t>::max() / 10) == -top);
  CHECK(dec(std::numeric_limits<std::int64_t>::max(), 0) == top);
  // Still in range, still exact: 4e9 mm.
  CHECK(Fixed::from_int(4'000'000'000) + Fixed::from_int(1) == Fixed::from_int(4'000'000'001));
  // Either side of 2^32, where from_decimal leaves its unchecked inline path.
  const std::int64_t edge = std::int64_t{1} << 32;
  for (std::int64_t m : {edge - 1, edge, edge + 1, -edge + 1, -edge, -edge - 1})
    for (int d = 0; d <= 9; ++d) CHECK(dec(m, d).units() == m * Fixed::kPowersOf10[9 - d]);
  CHECK(dec(std::int64_t{4'700'000'000}, 0) == top);  // 4.7e18 units: past kMax
  CHECK(dec(-std::int64_t{4'700'000'000}, 0) == -top);
  char b[gcode::kMaxNumberChars];
  CHECK(top.format(9, b) < gcode::kMaxNumberChars);
  CHECK((-top).format(9, b) < gcode::kMaxNumberChars);
}
