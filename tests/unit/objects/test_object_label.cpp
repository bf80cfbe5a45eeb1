// Reading object labels (objects/object_label.hpp, objects/object_tracker.hpp):
// each slicer's and firmware's words, as the public files write them; the
// firmware's labels win where a file declares them; Cura's mesh ends with
// its layer.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "gcode/core/line.hpp"
#include "gcode/objects/object_tracker.hpp"

using gcode::LabelDialect;
using gcode::LabelKind;

namespace test_object_label {

// The object of each line of `lines` (-1 none), a layer before each ";LAYER:".
std::vector<int> objects_of(const std::vector<std::string>& lines, gcode::ObjectTracker& tracker) {
  std::vector<int> out;
  for (const std::string& l : lines) {
    if (l.rfind(";LAYER:", 0) == 0) tracker.layer();
    out.push_back(tracker.line(gcode::Line::parse(l)));
  }
  return out;
}

gcode::LabelEvent read(gcode::LabelReader& r, const std::string& text) { return r.read(gcode::Line::parse(text)); }

}  // namespace test_object_label

using namespace test_object_label;

TEST_CASE("object labels: PrusaSlicer's comments give the name, the id and the copy", "[object_label]") {
  gcode::LabelReader r;
  gcode::LabelEvent e = read(r, "; printing object pegs.stl_7 id:6 copy 0");
  CHECK(e.kind == LabelKind::Start);
  CHECK(e.dialect == LabelDialect::Prusa);
  CHECK(e.name == "pegs.stl_7");
  CHECK(e.id == "6");
  e = read(r, "; printing object Shape Box id:3 copy 1");
  CHECK(e.name == "Shape Box");
  CHECK(e.id == "3.1");
  CHECK(read(r, "; stop printing object Shape Box id:3 copy 1").kind == LabelKind::Stop);
  CHECK(read(r, "; INIT printing object cube id:0 copy 0").kind == LabelKind::Start);
  CHECK(read(r, "G1 X1 Y2 E3").kind == LabelKind::None);
}

TEST_CASE("object labels: Cura's meshes end at the next mesh or layer, NONMESH is no object", "[object_label]") {
  gcode::ObjectTracker t;
  const std::vector<int> got = objects_of(
      {";MESH:left.stl", "G1 X1 Y1 E1", ";MESH:NONMESH", "G0 X5 Y5", ";MESH:right.stl", "G1 X2 Y2 E2", ";LAYER:1", "G0 Z0.4",
       ";MESH:left.stl", "G1 X1 Y1 E3"},
      t);
  CHECK(got == std::vector<int>{0, 0, -1, -1, 1, 1, -1, -1, 0, 0});
  REQUIRE(t.names().size() == 2);
  CHECK(t.names()[0].id == "0");
  CHECK(t.names()[1].name == "right.stl");
  CHECK(t.dialect() == LabelDialect::Cura);
}

TEST_CASE("object labels: ideaMaker names with PRINTING and numbers with PRINTING_ID, -1 is no object", "[object_label]") {
  gcode::ObjectTracker t;
  const std::vector<int> got = objects_of(
      {";PRINTING: test_bed_part0.3mf", ";PRINTING_ID: 0", "G1 X1 Y1 E1", ";PRINTING: NON-OBJECT", ";PRINTING_ID: -1",
       "G1 X9 Y9 E2", ";PRINTING: test_bed_part1.3mf", ";PRINTING_ID: 1", "G1 X2 Y2 E3"},
      t);
  CHECK(got == std::vector<int>{-1, 0, 0, 0, -1, -1, -1, 1, 1});
  REQUIRE(t.names().size() == 2);
  CHECK(t.names()[0].name == "test_bed_part0.3mf");
  CHECK(t.names()[1].id == "1");
}

TEST_CASE("object labels: Bambu Studio and OrcaSlicer's unique label ids", "[object_label]") {
  gcode::ObjectTracker t;
  const std::vector<int> got = objects_of(
      {"; start printing object, unique label id: 81", "M624 AQAAAAAAAAA=", "G1 X1 Y1 E1", "; stop printing object, unique label id: 81",
       "M625", "; start printing object, unique label id: 121", "G1 X2 Y2 E1"},
      t);
  CHECK(got == std::vector<int>{0, 0, 0, -1, -1, 1, 1});
  CHECK(t.names()[1].id == "121");
  CHECK(t.names()[1].name == "object 121");
}

TEST_CASE("object labels: Marlin's M486 with names, S-1 is no object", "[object_label]") {
  gcode::ObjectTracker t;
  const std::vector<int> got =
      objects_of({"M486 T2", "M486 S0 A\"cube id:0 copy 0\"", "G1 X1 Y1 E1", "M486 S-1", "M486 S1", "G1 X2 Y2 E2", "M486 S0", "G1 E3"}, t);
  CHECK(got == std::vector<int>{-1, 0, 0, -1, 1, 1, 0, 0});
  CHECK(t.names()[0].name == "cube id:0 copy 0");
  CHECK(t.names()[1].name == "object 1");
  CHECK(t.dialect() == LabelDialect::Marlin);
}

TEST_CASE("object labels: Klipper's EXCLUDE_OBJECT declares outlines and its labels win over the comments", "[object_label]") {
  gcode::ObjectTracker t;
  const std::vector<int> got = objects_of(
      {"EXCLUDE_OBJECT_DEFINE NAME=cube_id_0_copy_0 CENTER=110,110 POLYGON=[[105,105],[115,105],[115,115],[105,115]]",
       "EXCLUDE_OBJECT_DEFINE NAME=peg CENTER=130,110 POLYGON=[[128,108],[132,108],[132,112]]",
       "; printing object cube id:0 copy 0", "EXCLUDE_OBJECT_START NAME=cube_id_0_copy_0", "G1 X1 Y1 E1",
       "EXCLUDE_OBJECT_END NAME=cube_id_0_copy_0", "; stop printing object cube id:0 copy 0", "EXCLUDE_OBJECT_START NAME=peg",
       "G1 X2 Y2 E2"},
      t);
  CHECK(got == std::vector<int>{-1, -1, -1, 0, 0, -1, -1, 1, 1});
  REQUIRE(t.names().size() == 2);
  CHECK(t.names()[0].declared.size() == 4);
  CHECK(t.names()[1].declared[2].x == 132);
  CHECK(t.dialect() == LabelDialect::Klipper);
  CHECK(gcode::klipper_argument("NAME='a b' CENTER=1,2", "NAME") == "a b");
  CHECK(gcode::klipper_argument("XNAME=a NAME=b", "NAME") == "b");
}
