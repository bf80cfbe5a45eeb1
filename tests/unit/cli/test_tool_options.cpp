// The tools' options mapped to the library's configuration (cli/litho_options,
// cli/relayer_options, cli/layers_options): an option of the other mode is a
// usage error, the given values land in the configuration, the combinations
// a tool refuses are refused with its message.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "gcode/cli/layers_options.hpp"
#include "gcode/cli/litho_options.hpp"
#include "gcode/cli/relayer_options.hpp"
#include "tool_run.hpp"

namespace {

template <typename Options, typename Add>
int parse(Add add, std::vector<std::string> args, Options& o, std::string* err = nullptr) {
  gcode::cli::Tool tool("gc-test", "A test tool");
  add(tool, o);
  return gctest::parse_options(tool, std::move(args), err);
}

}  // namespace

TEST_CASE("litho options: each mode's configuration, the other mode's options refused", "[tool_options]") {
  std::string err;
  gcode::cli::LithoToolOptions flat;
  REQUIRE(parse(gcode::cli::add_litho_options, {"photo.png", "--center", "100,90", "--nozzle", "0.6", "--min", "1"},
                flat) == 0);
  CHECK(flat.plan.center_x == 100);
  CHECK(flat.plan.center_y == 90);
  CHECK(flat.plan.nozzle == 0.6);
  CHECK(flat.map.shape == gcode::litho::LithoShape::Flat);
  gcode::cli::LithoToolOptions paint;
  REQUIRE(parse(gcode::cli::add_litho_options,
                {"--texture", "face.png", "--projection", "sphere", "--center", "1,2,3", "--skip-z", "0.6", "--binary",
                 "0.4"},
                paint) == 0);
  CHECK(paint.mapping.projection == gcode::litho::Projection::Sphere);
  CHECK(paint.mapping.center_z == 3);
  CHECK(paint.where.z_range == "0.6:");  // nothing below is even cut
  CHECK(paint.speeds.binary);
  gcode::cli::LithoToolOptions mixed;
  CHECK(parse(gcode::cli::add_litho_options, {"--texture", "face.png", "--nozzle", "0.6"}, mixed, &err) == 2);
  CHECK(err == "gc-test: --nozzle makes a lithophane (mode 1); it does not go with --texture (see gc-test --help)\n");
  gcode::cli::LithoToolOptions mixed2;
  CHECK(parse(gcode::cli::add_litho_options, {"photo.png", "--low", "10"}, mixed2, &err) == 2);
  CHECK(err == "gc-test: --low paints a picture onto G-code; it goes with --texture IMAGE (see gc-test --help)\n");
  gcode::cli::LithoToolOptions cylinder;
  CHECK(parse(gcode::cli::add_litho_options, {"photo.png", "--shape", "cylinder", "--width", "50"}, cylinder, &err) ==
        2);
  CHECK(err == "gc-test: --width: a cylinder's width is its circumference; give --diameter (see gc-test --help)\n");
}

TEST_CASE("litho options: --start and --end are read, a missing one is an input error", "[tool_options]") {
  const std::string dir = gctest::temp_dir();
  gctest::write_file(dir + "/start.gcode", "G28\n");
  gcode::cli::LithoToolOptions o;
  o.start = dir + "/start.gcode";
  gcode::cli::load_litho_program(o);
  CHECK(o.gcode.start_code == "G28\n");
  CHECK(o.gcode.start_name == o.start);
  CHECK(o.gcode.end_code.empty());
  o.end = dir + "/none.gcode";
  CHECK_THROWS_WITH(gcode::cli::load_litho_program(o), "--end " + dir + "/none.gcode: cannot open it");
}

TEST_CASE("relayer options: one mode, the resume's plan options", "[tool_options]") {
  std::string err;
  gcode::cli::RelayerToolOptions none;
  CHECK(parse(gcode::cli::add_relayer_options, {"part.gcode"}, none, &err) == 2);
  CHECK(err == "gc-test: give one of --at-z, --at-layer, --resume-from-z or --list-candidates (see gc-test --help)\n");
  gcode::cli::RelayerToolOptions o;
  REQUIRE(parse(gcode::cli::add_relayer_options,
                {"--resume-from-z", "12.3", "--purge", "5", "--purge-at", "10,20", "--z-speed", "4", "part.gcode"},
                o) == 0);
  const gcode::ResumePlan::Options ro = gcode::cli::resume_plan_options(o);
  CHECK(ro.z == 12.3);
  CHECK(ro.purge == 5);
  CHECK(ro.purge_at_given);
  CHECK(ro.purge_x == 10);
  CHECK(ro.purge_y == 20);
  CHECK(ro.z_speed == 4);
  CHECK(ro.note_prefix == "gc-relayer: ");
  o.purge_at = "10";
  CHECK_THROWS_WITH(gcode::cli::resume_plan_options(o), "--purge-at: expected X,Y, not '10'");
  gcode::cli::RelayerToolOptions join;
  REQUIRE(parse(gcode::cli::add_relayer_options, {"--at-layer", "7", "new.gcode"}, join) == 0);
  CHECK(gcode::cli::join_plan_options(join).at_layer == 7);
  CHECK_FALSE(gcode::cli::join_plan_options(join).at_z);
}

TEST_CASE("layers options: the combinations gc-layers refuses", "[tool_options]") {
  std::string err;
  gcode::cli::LayersToolOptions o;
  CHECK(parse(gcode::cli::add_layers_options, {"-o", "out.gcode", "part.gcode"}, o, &err) == 2);
  CHECK(err == "gc-test: -o goes with --extract or --z-range (see gc-test --help)\n");
  gcode::cli::LayersToolOptions pictures;
  CHECK(parse(gcode::cli::add_layers_options, {"--svg", "3", "--json", "part.gcode"}, pictures, &err) == 2);
  CHECK(err == "gc-test: pictures do not combine with --extract, --z-range, --json or --where (see gc-test --help)\n");
  gcode::cli::LayersToolOptions cut;
  REQUIRE(parse(gcode::cli::add_layers_options, {"--extract", "2-4", "part.gcode"}, cut) == 0);
  CHECK(cut.cutting());
  CHECK_FALSE(cut.pictures());
}
