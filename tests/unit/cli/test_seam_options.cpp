// A seam's options (cli/seam_options.hpp): the same five options in every
// tool that joins G-code, defaults kept when not given, one validator style.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "gcode/cli/seam_options.hpp"
#include "capture.hpp"
#include "tool_run.hpp"

namespace {

int parse(std::vector<std::string> args, gcode::SeamOptions& o, std::string* err = nullptr) {
  gcode::cli::Tool tool("gc-test", "A test tool");
  gcode::cli::add_seam_options(tool, o);
  return gctest::parse_options(tool, std::move(args), err);
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

TEST_CASE("seam options: the splice's printer: the input's, a warning for another bed, its height for the lift",
          "[seam_options]") {
  const std::string dir = gctest::temp_dir();
  const std::string body = ";LAYER:0\nG1 Z0.2\nG1 X10 E1\n";
  gctest::write_file(dir + "/in.gcode", "; bed_shape = 0x0,250x0,250x210,0x210\n; max_print_height = 180\n" + body);
  gctest::write_file(dir + "/same.gcode", "; bed_shape = 0x0,250x0,250x210,0x210\n" + body);
  gctest::write_file(dir + "/other.gcode", "; bed_shape = 0x0,220x0,220x220,0x220\n" + body);
  gcode::cli::FilterOptions io;
  io.file = dir + "/in.gcode";
  gcode::cli::Filter run(io);
  gcode::InputFile same(dir + "/same.gcode"), other(dir + "/other.gcode");
  gcode::SeamOptions seam;
  gcode::PrintArea area;
  const std::string said = gctest::stderr_of([&] {
    gcode::Diagnostics diag("gc-test");
    area = gcode::cli::splice_printer(run, {{same.name(), same.fd(), nullptr}, {other.name(), other.fd(), nullptr}},
                                      seam, diag);
  });
  CHECK(area.has_bed);
  CHECK(area.bed.max_x == 250);
  CHECK(seam.max_z == 180);
  CHECK(said.find("other.gcode") != std::string::npos);  // one warning, for the other bed only
  CHECK(said.find("same.gcode") == std::string::npos);
  gcode::cli::FilterOptions low;
  low.file = dir + "/same.gcode";
  gcode::cli::Filter unknown(low);
  gcode::Diagnostics quiet("gc-test", -1);
  gcode::cli::splice_printer(unknown, {}, seam, quiet);
  CHECK(seam.max_z == 0);  // no height known: the lift has no ceiling
}

TEST_CASE("seam options: a splice's other files are opened and indexed once, standard input refused",
          "[seam_options]") {
  const std::string dir = gctest::temp_dir();
  gctest::write_file(dir + "/block.gcode", ";LAYER:0\nG1 Z0.2\nG1 X10 E1\n;LAYER:1\nG1 Z0.4\nG1 X0 E2\n");
  const gcode::LayerMarkers markers;
  gcode::cli::SpliceFiles files;
  const std::vector<gcode::SpliceFile> list = files.open({dir + "/block.gcode", dir + "/block.gcode"}, markers);
  REQUIRE(list.size() == 2);
  CHECK(list[0].name == dir + "/block.gcode");
  CHECK(list[0].fd == list[1].fd);  // one file, one index
  CHECK(list[0].index == list[1].index);
  list[0].index->read_all();
  CHECK(list[0].index->layers() == 2);
  CHECK_THROWS_AS(files.open({"-"}, markers), gcode::cli::UsageError);
}
