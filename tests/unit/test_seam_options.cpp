// A seam's options (cli/seam_options.hpp): the same five options in every
// tool that joins G-code, defaults kept when not given, one validator style.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "gcode/cli/seam_options.hpp"
#include "capture.hpp"

namespace {

int parse(std::vector<std::string> args, gcode::SeamOptions& o, std::string* err = nullptr) {
  gcode::cli::Tool tool("gc-test", "A test tool");
  gcode::cli::add_seam_options(tool, o);
  args.insert(args.begin(), "gc-test");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  int status = -1;
  std::string e = gctest::stderr_of([&] { status = tool.run(static_cast<int>(args.size()), argv.data(), [] { return 0; }); });
  if (err != nullptr) *err = e;
  return status;
}

}  // namespace

TEST_CASE("seam options: each option sets its field, the rest keep their defaults", "[seam_options]") {
  gcode::SeamOptions o;
  REQUIRE(parse({"--lift", "0.6", "--travel-speed", "120"}, o) == 0);
  CHECK(o.lift == 0.6);
  CHECK(o.travel_speed == 120);
  CHECK(o.retract == 1);
  CHECK(o.retract_speed == 35);
  CHECK(o.z_speed == 10);
  REQUIRE(parse({"--retract", "0", "--retract-speed", "45", "--z-speed", "5", "--lift", "0"}, o) == 0);
  CHECK(o.retract == 0);  // 0: never retract
  CHECK(o.retract_speed == 45);
  CHECK(o.z_speed == 5);
  CHECK(o.lift == 0);
}

TEST_CASE("seam options: lengths may be 0, speeds must be positive", "[seam_options]") {
  gcode::SeamOptions o;
  std::string err;
  CHECK(parse({"--lift", "-1"}, o, &err) == 2);
  CHECK(err == "gc-test: --lift: must be a number >= 0, not '-1' (see gc-test --help)\n");
  CHECK(parse({"--retract", "x"}, o, &err) == 2);
  CHECK(err == "gc-test: --retract: must be a number >= 0, not 'x' (see gc-test --help)\n");
  for (const char* speed : {"--retract-speed", "--travel-speed", "--z-speed"}) {
    CHECK(parse({speed, "0"}, o, &err) == 2);
    CHECK(err == std::string("gc-test: ") + speed + ": must be a number > 0, not '0' (see gc-test --help)\n");
  }
}
