// The user's G-code for a block (transform/custom_gcode.hpp): a regular file
// is read whole, byte for byte; anything else is text whose "\n" (backslash,
// n) become newlines.
#include <catch2/catch.hpp>

#include <string>

using namespace std::string_literals;

#include "gcode/transform/custom_gcode.hpp"
#include "test_support.hpp"

using gcode::load_custom_gcode;

TEST_CASE("custom gcode: a file is read whole, byte for byte", "[custom_gcode]") {
  std::string path = gctest::temp_dir() + "/before.gcode";
  std::string text = "M117 Change filament\r\nG1 E-5 F1800 ; a \\n stays as written\nM300\0 S440"s;
  gctest::write_file(path, text);
  CHECK(load_custom_gcode(path) == text);
  std::string empty = gctest::temp_dir() + "/empty.gcode";
  gctest::write_file(empty, "");
  CHECK(load_custom_gcode(empty).empty());
}

TEST_CASE("custom gcode: text with backslash-n between lines", "[custom_gcode]") {
  CHECK(load_custom_gcode("M117 Pause\\nM0") == "M117 Pause\nM0");
  CHECK(load_custom_gcode("G1 Z10\\n\\nM0\\n") == "G1 Z10\n\nM0\n");
  CHECK(load_custom_gcode("M0") == "M0");
  CHECK(load_custom_gcode("").empty());
  // Only backslash-n is special.
  CHECK(load_custom_gcode("a\\tb\\") == "a\\tb\\");
  CHECK(load_custom_gcode("\\\\n") == "\\\n");
  CHECK(load_custom_gcode("M117 n\\") == "M117 n\\");
}

TEST_CASE("custom gcode: what is not a regular file is text", "[custom_gcode]") {
  std::string dir = gctest::temp_dir();
  CHECK(load_custom_gcode(dir) == dir);  // a directory is not read
  std::string missing = dir + "/no-such-file.gcode";
  CHECK(load_custom_gcode(missing) == missing);
}
