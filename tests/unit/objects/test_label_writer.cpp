// Firmware labels (objects/label_writer.hpp): Klipper's DEFINE before the
// first layer and START/END around each block, M486 with the name once;
// every input line unchanged; Klipper's names made safe and unique.
#include <catch2/catch.hpp>

#include <string>

#include "gcode/objects/label_writer.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "test_support.hpp"

namespace test_label_writer {

const char* const kLabelPlate =
    "G90\nM83\n;LAYER_CHANGE\n;Z:0.2\nG1 Z0.2 F600\n"
    "; printing object a b id:0 copy 0\nG1 X0 Y0\nG1 X10 Y0 E1\n; stop printing object a b id:0 copy 0\n"
    "; printing object c id:1 copy 0\nG1 X20 Y0\nG1 X30 Y10 E1\n; stop printing object c id:1 copy 0\n"
    ";LAYER_CHANGE\n;Z:0.4\nG1 Z0.4\n"
    "; printing object a b id:0 copy 0\nG1 X10 Y0\nG1 X0 Y0 E1\n; stop printing object a b id:0 copy 0\n";

gcode::ObjectTable table_of(const std::string& text) {
  gcode::ObjectTableStage stage;
  gctest::run_stages(text, {&stage});
  return stage.table();
}

std::string labelled(const std::string& text, gcode::FirmwareLabels kind) {
  const gcode::ObjectTable table = table_of(text);
  gcode::LabelWriter writer(table, kind);
  return gctest::run_stages(text, {&writer});
}

}  // namespace test_label_writer

using namespace test_label_writer;

TEST_CASE("label writer: Klipper's outlines before the first layer and START/END around each block", "[label_writer]") {
  const std::string out = labelled(kLabelPlate, gcode::FirmwareLabels::Klipper);
  CHECK_THAT(out, Catch::Contains("EXCLUDE_OBJECT_DEFINE NAME=a_b CENTER=5.000,0.000 POLYGON=[[0.000,0.000],[10.000,0.000]]\n"
                                  "EXCLUDE_OBJECT_DEFINE NAME=c CENTER=25.000,5.000"));
  CHECK_THAT(out, Catch::Contains("; printing object a b id:0 copy 0\nEXCLUDE_OBJECT_START NAME=a_b\nG1 X0 Y0\n"));
  CHECK_THAT(out, Catch::Contains("E1\nEXCLUDE_OBJECT_END NAME=a_b\n; stop printing object a b id:0 copy 0\n"));
  CHECK(out.find("EXCLUDE_OBJECT_DEFINE") < out.find(";LAYER_CHANGE"));
  // Every input line is there, in order.
  std::string kept;
  std::size_t at = 0;
  while (at < out.size()) {
    const std::size_t nl = out.find('\n', at);
    const std::string line = out.substr(at, nl + 1 - at);
    if (line.rfind("EXCLUDE_OBJECT", 0) != 0) kept += line;
    at = nl + 1;
  }
  CHECK(kept == kLabelPlate);
}

TEST_CASE("label writer: M486 counts the objects, names each once, and ends each block with S-1", "[label_writer]") {
  const std::string out = labelled(kLabelPlate, gcode::FirmwareLabels::Marlin);
  CHECK_THAT(out, Catch::StartsWith("G90\nM83\nM486 T2\n;LAYER_CHANGE\n"));
  CHECK_THAT(out, Catch::Contains("; printing object a b id:0 copy 0\nM486 S0 A\"a b\"\n"));
  CHECK_THAT(out, Catch::Contains("; printing object c id:1 copy 0\nM486 S1 A\"c\"\n"));
  CHECK_THAT(out, Catch::EndsWith("; printing object a b id:0 copy 0\nM486 S0\nG1 X10 Y0\nG1 X0 Y0 E1\nM486 S-1\n; stop printing object a b id:0 copy 0\n"));
}

TEST_CASE("label writer: copies that share a name get their ids in Klipper's names", "[label_writer]") {
  gcode::ObjectTable t;
  t.objects.resize(3);
  t.objects[0].name = "cube.stl";
  t.objects[0].id = "0";
  t.objects[1].name = "cube.stl";
  t.objects[1].id = "0.1";
  t.objects[2].name = "peg (2)";
  t.objects[2].id = "1";
  CHECK(gcode::klipper_names(t) == std::vector<std::string>{"cube.stl_id_0", "cube.stl_id_0.1", "peg__2_"});
}
