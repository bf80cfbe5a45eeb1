// {name} placeholders (core/placeholders.hpp): every occurrence replaced,
// unknown names and stray braces left as written, values not expanded again.
#include <catch2/catch.hpp>

#include "gcode/core/placeholders.hpp"

using gcode::expand_placeholders;
using gcode::has_placeholder;
using gcode::Placeholders;

TEST_CASE("placeholders: every occurrence of a known name is replaced", "[placeholders]") {
  Placeholders v{{"layer", "12"}, {"z", "2.4"}};
  CHECK(expand_placeholders("Paused at layer {layer}, Z {z}", v) == "Paused at layer 12, Z 2.4");
  CHECK(expand_placeholders("{layer}{layer}-{z}", v) == "1212-2.4");
  CHECK(expand_placeholders("M117 {layer}\nM300 S{z}\n", v) == "M117 12\nM300 S2.4\n");
  CHECK(expand_placeholders("no placeholder", v) == "no placeholder");
  CHECK(expand_placeholders("", v).empty());
}

TEST_CASE("placeholders: {} is the empty name (an output pattern)", "[placeholders]") {
  Placeholders v{{"", "007"}};
  CHECK(expand_placeholders("layer-{}.svg", v) == "layer-007.svg");
  CHECK(expand_placeholders("layer-{layer}.svg", v) == "layer-{layer}.svg");
}

TEST_CASE("placeholders: unknown names and stray braces stay as written", "[placeholders]") {
  Placeholders v{{"layer", "3"}};
  CHECK(expand_placeholders("{height} at {layer}", v) == "{height} at 3");
  CHECK(expand_placeholders("{{layer}}", v) == "{3}");
  CHECK(expand_placeholders("{a{layer}", v) == "{a3");
  CHECK(expand_placeholders("{layer", v) == "{layer");
  CHECK(expand_placeholders("layer}", v) == "layer}");
  CHECK(expand_placeholders("}{layer}{", v) == "}3{");
  CHECK(expand_placeholders("{LAYER}", v) == "{LAYER}");  // names are exact
}

TEST_CASE("placeholders: a value is text, never expanded again", "[placeholders]") {
  Placeholders v{{"a", "{b}"}, {"b", "x"}};
  CHECK(expand_placeholders("{a}", v) == "{b}");
  CHECK(expand_placeholders("{a}{b}", v) == "{b}x");
}

TEST_CASE("placeholders: has_placeholder finds {name} exactly", "[placeholders]") {
  CHECK(has_placeholder("layer-{}.svg", ""));
  CHECK(has_placeholder("at {z} mm", "z"));
  CHECK_FALSE(has_placeholder("at {zz} mm", "z"));
  CHECK_FALSE(has_placeholder("at {z mm", "z"));
  CHECK_FALSE(has_placeholder("at z} mm", "z"));
  CHECK(has_placeholder("{x}{z}", "z"));
  CHECK(has_placeholder("{{z}", "z"));
  CHECK_FALSE(has_placeholder("", ""));
}
