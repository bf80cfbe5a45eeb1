// The simulated printer's options (gcode/serial/sim/virtual_printer_options.hpp):
// "key=value,..." after "virtual:" sets the configuration; a bad key or
// value is refused by name.
#include <catch2/catch.hpp>

#include <stdexcept>

#include "gcode/serial/sim/virtual_printer_options.hpp"

using namespace gcode::serial;

TEST_CASE("virtual printer options: keys set the configuration", "[serial][virtual_printer_options]") {
  VirtualPrinterConfig config;
  parse_virtual_options("time-scale=20,baud=115200,instant-moves=on", config);
  CHECK(config.time_scale == 20);
  CHECK(config.baud == 115200);
  CHECK(config.instant_moves);
}

TEST_CASE("virtual printer options: a bad key or value is refused", "[serial][virtual_printer_options]") {
  VirtualPrinterConfig config;
  CHECK_THROWS_AS(parse_virtual_options("no-such-key=1", config), std::invalid_argument);
  CHECK_THROWS_AS(parse_virtual_options("baud=fast", config), std::invalid_argument);
  CHECK_THROWS_AS(parse_virtual_options("instant-moves=maybe", config), std::invalid_argument);
}
