// transform/expression.hpp: muparser behind one header; names bound by the
// caller, pi defined, errors with their position.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "gcode/transform/expression.hpp"

using gcode::Expression;
using gcode::ExpressionError;

TEST_CASE("an expression evaluates with the variables the caller sets, pi included", "[expression]") {
  double r = 0, z = 0;
  const Expression e("r + 1.05*z + 0*pi", {{"r", &r}, {"z", &z}});
  r = 30, z = 10;
  CHECK(e.evaluate() == Approx(40.5));
  r = 1;
  CHECK(e.evaluate() == Approx(11.5));
  const Expression s("20*sin(pi*z/20) + (z > 5 ? 1 : 0) + abs(-2)^2", {{"z", &z}});
  CHECK(s.evaluate() == Approx(20 * std::sin(std::numbers::pi / 2) + 1 + 4));
  CHECK(s.uses("z"));
  CHECK_FALSE(e.uses("x"));
  CHECK(e.text() == "r + 1.05*z + 0*pi");
}

TEST_CASE("bad syntax and unknown names are errors with the 1-based position", "[expression]") {
  double x = 0;
  auto position = [&](const char* text) {
    try {
      Expression e(text, {{"x", &x}});
      return -1;
    } catch (const ExpressionError& err) {
      CHECK(std::string(err.what()).size() > 5);
      return err.position;
    }
  };
  CHECK(position("x + y") == 5);
  CHECK(position("x + * 2") == 5);
  CHECK(position("sin(x") > 0);
  CHECK(position("") >= 0);
  CHECK(position("x*2") == -1);
}

TEST_CASE("domain errors give NaN or infinity, never an exception", "[expression]") {
  double x = -1;
  const Expression root("sqrt(x)", {{"x", &x}});
  CHECK(std::isnan(root.evaluate()));
  x = 0;
  const Expression inverse("1/x", {{"x", &x}});
  CHECK(std::isinf(inverse.evaluate()));
  const Expression log("ln(x)", {{"x", &x}});
  CHECK_FALSE(std::isfinite(log.evaluate()));
}
