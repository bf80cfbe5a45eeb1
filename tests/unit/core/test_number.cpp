#include <catch2/catch.hpp>

#include <cmath>

#include "gcode/core/number.hpp"

using gcode::parse_number;

TEST_CASE("parse_number reads slicer decimals exactly", "[number]") {
  double v = 0;
  CHECK((parse_number("12.345", v) && v == 12.345));
  CHECK((parse_number("-.8", v) && v == -0.8));
  CHECK((parse_number("+10", v) && v == 10));
  CHECK((parse_number(".2", v) && v == 0.2));
  CHECK((parse_number("5.", v) && v == 5));
  CHECK((parse_number("7800.000", v) && v == 7800));
  CHECK((parse_number("0.00001", v) && v == 0.00001));
  CHECK((parse_number("1e3", v) && v == 1000));
  CHECK((parse_number("12345678901234567890", v) && v == 12345678901234567890.0));
}

TEST_CASE("parse_number rejects what is not a number", "[number]") {
  double v = 0;
  CHECK_FALSE(parse_number("", v));
  CHECK_FALSE(parse_number("-", v));
  CHECK_FALSE(parse_number(".", v));
  CHECK_FALSE(parse_number("1.2.3", v));
  CHECK_FALSE(parse_number("12abc", v));
  CHECK_FALSE(parse_number("nan", v));
  CHECK_FALSE(parse_number("1e309", v));
}

TEST_CASE("format_number writes the shortest fixed decimal", "[number]") {
  char b[gcode::kMaxNumberChars];
  CHECK(gcode::number_text(12.5, 3, b) == "12.5");
  CHECK(gcode::number_text(12.0, 3, b) == "12");
  CHECK(gcode::number_text(-0.0001, 3, b) == "0");
  CHECK(gcode::number_text(-0.04, 3, b) == "-0.04");
  CHECK(gcode::number_text(0.1 + 0.2, 5, b) == "0.3");
  CHECK(gcode::number_text(1234.56789, 2, b) == "1234.57");
  CHECK(gcode::number_text(1e20, 3, b) == "1000000000000000");
  CHECK(gcode::number_text(std::nan(""), 3, b) == "0");
  CHECK(gcode::number_text(0.000005, 5, b) == "0.00001");
}

TEST_CASE("format then parse round-trips at the given precision", "[number][property]") {
  char b[gcode::kMaxNumberChars];
  for (int i = -20000; i <= 20000; i += 7) {
    double x = i * 0.001;
    double back = 0;
    REQUIRE(parse_number(gcode::number_text(x, 3, b), back));
    REQUIRE(std::fabs(back - x) < 1e-9);
  }
}

TEST_CASE("decimals_of counts digits after the point", "[number]") {
  CHECK(gcode::decimals_of("0.125") == 3);
  CHECK(gcode::decimals_of("5") == 0);
  CHECK(gcode::decimals_of("-.80") == 2);
}

TEST_CASE("format_scaled writes a scaled integer exactly as format_number writes the value", "[number]") {
  char a[gcode::kMaxNumberChars], b[gcode::kMaxNumberChars];
  auto scaled = [&](std::int64_t units, int decimals) {
    return std::string(a, gcode::format_scaled(units, decimals, a));
  };
  CHECK(scaled(12345, 5) == "0.12345");
  CHECK(scaled(-7, 5) == "-0.00007");
  CHECK(scaled(120, 3) == "0.12");
  CHECK(scaled(0, 3) == "0");
  CHECK(scaled(-5000, 3) == "-5");
  for (std::int64_t u = -300000; u <= 300000; u += 997)
    for (int d : {0, 3, 5})
      REQUIRE(scaled(u, d) == gcode::number_text(static_cast<double>(u) / std::pow(10.0, d), d, b));
  // Halves round away from zero, huge values are clamped, never undefined.
  CHECK(gcode::number_text(0.0005, 3, b) == "0.001");
  CHECK(gcode::number_text(-2.5, 0, b) == "-3");
  CHECK(gcode::number_text(1e300, 9, b).size() > 0);
}

TEST_CASE("number_string spells a value as the messages and generated G-code write it", "[number]") {
  using gcode::number_string;
  // Rounding: half away from zero at the decimals asked for.
  CHECK(number_string(0.03125, 4) == "0.0313");
  CHECK(number_string(-0.03125, 4) == "-0.0313");
  CHECK(number_string(1.25, 1) == "1.3");
  CHECK(number_string(0.2 + 0.1, 4) == "0.3");
  CHECK(number_string(7.5, 0) == "8");
  // Trailing zeros and a bare point dropped.
  CHECK(number_string(0.2, 3) == "0.2");
  CHECK(number_string(12.0, 4) == "12");
  CHECK(number_string(100.10, 3) == "100.1");
  // -0, and a negative value that rounds to zero, are "0".
  CHECK(number_string(-0.0, 3) == "0");
  CHECK(number_string(-0.0004, 3) == "0");
  // Large values are written in full, never with an exponent; beyond 1e15 clamped.
  CHECK(number_string(123456789.25, 2) == "123456789.25");
  CHECK(number_string(-1e12, 3) == "-1000000000000");
  CHECK(number_string(1e20, 3) == "1000000000000000");
  // The same text as number_text at every precision.
  char b[gcode::kMaxNumberChars];
  for (int d = 0; d <= 9; ++d)
    for (double v : {0.0, 1.0 / 3, -2.675, 1234.5678901, 0.1 + 0.2})
      REQUIRE(number_string(v, d) == gcode::number_text(v, d, b));
}
