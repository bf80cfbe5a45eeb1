// gc-objects on real slicer output: the table and its JSON, and --exclude
// checked by the independent replay checker (tests/support/objects/
// object_check.hpp) on every labelled fixture, leaving out each object in
// turn; --from-layer; the errors.
#include <catch2/catch.hpp>

#include "objects/object_check.hpp"
#include "test_support.hpp"

using gctest::fixture_path;
using gctest::read_file;
using gctest::run;

namespace test_gc_objects {

// The fixtures with object labels of several objects, each slicer's.
const char* const kLabelled[] = {"prusa_pegs_0.2_klipper_zhop_labels.gcode", "objects/cura_3objects_abs_zhop_support.gcode",
                                 "objects/cura_3objects_rel_fwretract.gcode", "objects/prusa_3objects_abs_wipe_zhop_support.gcode",
                                 "objects/prusa_3objects_rrf_fwretract.gcode", "objects/prusa_cube_3copies_klipper_rel.gcode"};

nlohmann::json objects_of(const std::string& path) {
  auto r = run(gctest::tool_command("gc-objects", "--json " + gctest::quote(path)));
  REQUIRE(r.status == 0);
  return nlohmann::json::parse(r.out)["objects"];
}

// The checker names an object by its label's number, else its name.
std::vector<std::string> checker_names(const nlohmann::json& o) {
  return {o["id"].get<std::string>(), o["name"].get<std::string>()};
}

}  // namespace test_gc_objects

using namespace test_gc_objects;

TEST_CASE("gc-objects: lists the labelled objects of a plate with their boxes, layers and filament", "[gc-objects]") {
  const nlohmann::json objects = objects_of(fixture_path("prusa_pegs_0.2_klipper_zhop_labels.gcode"));
  REQUIRE(objects.size() == 12);
  for (const auto& o : objects) {
    CHECK(o["source"] == "labels");
    CHECK(o["first_layer"] == 1);
    CHECK(o["filament_mm"].get<double>() > 50);
    CHECK(o["time_s"].get<double>() > 30);
    CHECK(o["polygon"].size() >= 3);
    const auto& b = o["bbox"];
    CHECK(b[2].get<double>() - b[0].get<double>() == Approx(5.5).margin(0.6));
  }
  CHECK(objects[0]["id"] == "0");
  CHECK(objects[0]["name"] == "pegs.stl_1");
  CHECK(objects[0]["last_layer"] == 40);
}

TEST_CASE("gc-objects --exclude: every labelled fixture, each object left out in turn, checked by replay", "[gc-objects]") {
  for (const char* name : kLabelled) {
    const std::string path = fixture_path(name);
    const std::string input = read_file(path);
    const nlohmann::json objects = objects_of(path);
    for (const auto& o : objects) {
      const std::string id = o["id"].get<std::string>();
      INFO(name << " without object " << id);
      auto r = run(gctest::tool_command("gc-objects", "--exclude " + gctest::quote(id) + " " + gctest::quote(path)));
      REQUIRE(r.status == 0);
      const gctest::ObjectCheck c = gctest::check_objects_left_out(input, r.out, checker_names(o));
      CHECK(c.message == "");
      CHECK(c.left_out > 0);
      CHECK(c.kept > 0);
    }
  }
}

TEST_CASE("gc-objects --exclude --from-layer: a part that came loose is left out from that layer on", "[gc-objects]") {
  const std::string path = fixture_path("prusa_pegs_0.2_klipper_zhop_labels.gcode");
  const std::string input = read_file(path);
  auto r = run(gctest::tool_command("gc-objects", "--exclude pegs.stl_8,3 --from-layer 30 " + gctest::quote(path)));
  REQUIRE(r.status == 0);
  const gctest::ObjectCheck c = gctest::check_objects_left_out(input, r.out, {"7", "3"}, 30);
  CHECK(c.message == "");
  CHECK(c.left_out > 0);
}

TEST_CASE("gc-objects: an unknown object is a usage error listing the objects, leaving all out is refused", "[gc-objects]") {
  const std::string path = fixture_path("prusa_pegs_0.2_klipper_zhop_labels.gcode");
  auto r = run(gctest::tool_command("gc-objects", "--exclude 99 " + gctest::quote(path)));
  CHECK(r.status == 2);
  CHECK_THAT(r.err, Catch::Contains("no object '99'") && Catch::Contains("pegs.stl_12"));
  CHECK(r.out.empty());
  r = run(gctest::tool_command("gc-objects", "--exclude 0,1,2,3,4,5,6,7,8,9,10,11 " + gctest::quote(path)));
  CHECK(r.status == 1);
  CHECK_THAT(r.err, Catch::Contains("all 12 objects"));
  r = run(gctest::tool_command("gc-objects", "--exclude 0 " + gctest::quote(fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode"))));
  CHECK(r.status == 1);
  CHECK_THAT(r.err, Catch::Contains("has one object"));
}

namespace test_gc_objects {

// Every line of the labelled blocks of `id` cut out (what a naive filter does).
std::string cut_blocks(const std::string& input, const std::string& label) {
  std::string out;
  bool in = false;
  std::size_t at = 0;
  while (at < input.size()) {
    std::size_t nl = input.find('\n', at);
    if (nl == std::string::npos) nl = input.size() - 1;
    const std::string line = input.substr(at, nl + 1 - at);
    if (line.rfind("; printing object " + label, 0) == 0) in = true;
    if (!in) out += line;
    if (line.rfind("; stop printing object " + label, 0) == 0) in = false;
    at = nl + 1;
  }
  return out;
}

}  // namespace test_gc_objects

TEST_CASE("object checker: it catches a cut of whole blocks in absolute E, and the input left as it was", "[gc-objects]") {
  const std::string input = read_file(fixture_path("objects/prusa_3objects_abs_wipe_zhop_support.gcode"));
  gctest::ObjectCheck c = gctest::check_objects_left_out(input, cut_blocks(input, "tshape id:1"), {"1"});
  CHECK_FALSE(c.ok);
  CHECK_THAT(c.message, Catch::Contains("extrusion"));
  c = gctest::check_objects_left_out(input, input, {"1"});
  CHECK_FALSE(c.ok);
  c = gctest::check_objects_left_out(input, input, {"7"});
  CHECK(c.ok);
  CHECK(c.left_out == 0);
}

TEST_CASE("gc-objects --label: Klipper's and Marlin's labels name the same objects, and they can be left out by them",
          "[gc-objects]") {
  const std::string dir = gctest::temp_dir();
  for (const char* name : kLabelled) {
    const std::string path = fixture_path(name);
    const nlohmann::json slicer = objects_of(path);
    for (const char* kind : {"klipper", "marlin"}) {
      INFO(name << " labelled for " << kind);
      const std::string labelled = dir + "/" + kind + ".gcode";
      auto r = run(gctest::tool_command("gc-objects", std::string("--label ") + kind + " " + gctest::quote(path) + " -o " + labelled));
      REQUIRE(r.status == 0);
      const nlohmann::json firmware = objects_of(labelled);
      REQUIRE(firmware.size() == slicer.size());
      for (std::size_t i = 0; i < slicer.size(); ++i) {
        CHECK(firmware[i]["bbox"] == slicer[i]["bbox"]);
        CHECK(firmware[i]["filament_mm"] == slicer[i]["filament_mm"]);
      }
      const std::string text = read_file(labelled);
      const auto& o = firmware[firmware.size() / 2];
      r = run(gctest::tool_command("gc-objects", "--exclude " + gctest::quote(o["id"].get<std::string>()) + " " + labelled));
      REQUIRE(r.status == 0);
      const gctest::ObjectCheck c = gctest::check_objects_left_out(text, r.out, checker_names(o));
      CHECK(c.message == "");
      CHECK(c.left_out > 0);
    }
  }
  // A file labelled for the firmware already is refused.
  auto r = run(gctest::tool_command("gc-objects", "--label klipper " + dir + "/marlin.gcode"));
  CHECK(r.status == 1);
  CHECK_THAT(r.err, Catch::Contains("firmware labels already"));
}

TEST_CASE("gc-objects: a file without labels, objects from their footprints, each left out in turn", "[gc-objects]") {
  // The plate of objects/README.md: three 10 mm cubes placed by make_amf.py.
  const std::vector<std::string> boxes = {"box:94.5,94.5,105.5,105.5", "box:114.5,119.5,125.5,130.5", "box:134.5,94.5,145.5,105.5"};
  for (const char* name : {"objects/slic3r_3objects_abs_skirt_unlabelled.gcode", "objects/slic3r_3objects_rel_lift_wipe_unlabelled.gcode"}) {
    const std::string path = fixture_path(name);
    const std::string input = read_file(path);
    const nlohmann::json objects = objects_of(path);
    REQUIRE(objects.size() == 3);
    for (std::size_t i = 0; i < objects.size(); ++i) {
      INFO(name << " without footprint " << i);
      CHECK(objects[i]["source"] == "footprint");
      auto r = run(gctest::tool_command("gc-objects", "--exclude " + std::to_string(i) + " " + gctest::quote(path)));
      REQUIRE(r.status == 0);
      const gctest::ObjectCheck c = gctest::check_objects_left_out(input, r.out, {boxes[i]});
      CHECK(c.message == "");
      CHECK(c.left_out > 0);
    }
  }
}

TEST_CASE("gc-objects: footprints that later extrusions join cannot be cut (exit 1, saying where)", "[gc-objects]") {
  // A T on one stem with support: its support pillars stand apart on the
  // first layer, and the bar joins them higher up.
  const std::string path = fixture_path("slic3r_tshape_0.2_support_unmarked.gcode");
  auto r = run(gctest::tool_command("gc-objects", "--exclude 0 " + gctest::quote(path)));
  CHECK(r.status == 1);
  CHECK_THAT(r.err, Catch::Contains("cannot be cut") && Catch::Contains("line "));
  CHECK(r.out.empty());
}
