#include <catch2/catch.hpp>

#include "gcode/core/layer_range.hpp"

using gcode::LayerRange;
using gcode::ZRange;

TEST_CASE("layer ranges in every form", "[layer_range]") {
  auto one = LayerRange::parse("5");
  CHECK(one.contains(5));
  CHECK_FALSE(one.contains(4));
  CHECK_FALSE(one.contains(6));
  auto span = LayerRange::parse("5-9");
  CHECK(span.contains(5));
  CHECK(span.contains(9));
  CHECK_FALSE(span.contains(10));
  auto open = LayerRange::parse("5-");
  CHECK(open.contains(5000));
  CHECK_FALSE(open.contains(4));
  auto last = LayerRange::parse("-3");
  CHECK(last.needs_total());
  CHECK(last.contains(98, 100));
  CHECK(last.contains(100, 100));
  CHECK_FALSE(last.contains(97, 100));
  CHECK(last.lowest(100) == 98);
  auto list = LayerRange::parse("5,7,9-12");
  CHECK(list.contains(7));
  CHECK_FALSE(list.contains(8));
  CHECK(list.contains(11));
  CHECK(list.highest_named() == 12);
  CHECK(list.lowest(100) == 5);
}

TEST_CASE("bad layer ranges say what is wrong", "[layer_range]") {
  CHECK_THROWS_AS(LayerRange::parse(""), std::invalid_argument);
  CHECK_THROWS_AS(LayerRange::parse("0"), std::invalid_argument);
  CHECK_THROWS_AS(LayerRange::parse("9-5"), std::invalid_argument);
  CHECK_THROWS_AS(LayerRange::parse("a"), std::invalid_argument);
  CHECK_THROWS_AS(LayerRange::parse("5,,6"), std::invalid_argument);
  CHECK_THROWS_WITH(LayerRange::parse("3-x"), Catch::Contains("'x'"));
}

TEST_CASE("Z ranges", "[layer_range]") {
  auto z = ZRange::parse("0.2:1");
  CHECK(z.contains(0.2));
  CHECK(z.contains(1));
  CHECK_FALSE(z.contains(1.2));
  CHECK(ZRange::parse(":5").contains(-3));
  CHECK(ZRange::parse("5:").contains(500));
  CHECK_THROWS(ZRange::parse("5"));
  CHECK_THROWS(ZRange::parse("5:1"));
  CHECK_THROWS(ZRange::parse("a:1"));
}
