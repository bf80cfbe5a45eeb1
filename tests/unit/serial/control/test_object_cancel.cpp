// gc-send's object cancel (gcode/serial/control/object_cancel.hpp): the
// words of `cancel object` and --exclude; an object cancelled by id, name
// or before it appears; a cancel in the middle of a block stops it at the
// next line; a resume's printed part names the objects and the one the
// stream stands in; the journal's text and the status file's list.
#include <catch2/catch.hpp>

#include <string>

#include "fn_stage.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "gcode/serial/control/control_fifo.hpp"
#include "gcode/serial/control/object_cancel.hpp"
#include "test_support.hpp"

namespace test_object_cancel {

// Two objects (PrusaSlicer's labels), absolute E: A, B, then A again.
const char* const kCancelPlate =
    "M82\nG90\nG92 E0\n;LAYER_CHANGE\n;Z:0.2\nG1 Z0.2 F600\n"
    "; printing object A id:0 copy 0\nG1 X0 Y0 F6000\nG1 X10 Y0 E1 F1200\nG1 X10 Y10 E2\n"
    "; stop printing object A id:0 copy 0\n"
    "; printing object B id:1 copy 0\nG1 X50 Y50 F6000\nG1 X60 Y50 E3 F1200\nG1 X60 Y60 E4\n"
    "; stop printing object B id:1 copy 0\n"
    "; printing object A id:0 copy 0\nG1 X10 Y10 F6000\nG1 X0 Y10 E5 F1200\n"
    "; stop printing object A id:0 copy 0\n";

int cancel_count_of(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

}  // namespace test_object_cancel

using namespace test_object_cancel;

TEST_CASE("object cancel: the objects a line names, by blanks, commas and quotes", "[object_cancel]") {
  using V = std::vector<std::string>;
  CHECK(gcode::serial::object_terms("3") == V{"3"});
  CHECK(gcode::serial::object_terms(" 3, 5 pegs.stl_1,,") == V{"3", "5", "pegs.stl_1"});
  CHECK(gcode::serial::object_terms("\"my part.stl\" 2") == V{"my part.stl", "2"});
  CHECK(gcode::serial::object_terms("").empty());
}

TEST_CASE("object cancel: `cancel object` and `objects` are read, `cancel` alone stays the print's", "[object_cancel]") {
  using gcode::serial::parse_control_command;
  auto c = parse_control_command("Cancel Object 3 \"a b\"");
  CHECK(c.is("cancel object"));
  CHECK(c.argument == "3 \"a b\"");
  CHECK(parse_control_command("cancel").is("cancel"));
  CHECK(parse_control_command("cancel object").verb == nullptr);
  CHECK(parse_control_command("cancel objectX").verb == nullptr);
  CHECK(parse_control_command("objects").is("objects"));
  CHECK(parse_control_command("objects 3").verb == nullptr);
}

TEST_CASE("object cancel: --exclude by name leaves every block of it out, by id too", "[object_cancel]") {
  for (const char* term : {"B", "b", "1"}) {
    INFO(term);
    gcode::Diagnostics diag("test");
    gcode::LayerMarkers markers;
    gcode::Pipeline p(markers);
    gcode::serial::ObjectCancel objects(diag, p.precision());
    objects.exclude({term}, "--exclude", true);
    objects.add_stage(p, 0);
    const std::string out = gctest::run_stages(p, kCancelPlate);
    INFO(out);
    CHECK(out.find("E3 ") == std::string::npos);
    CHECK(out.find("G1 X60 Y60 E4") == std::string::npos);
    CHECK(out.find("G92 E4") != std::string::npos);
    CHECK(out.find("G1 X0 Y10 E5 F1200") != std::string::npos);
    CHECK(objects.journal_text() == "p:B id:1 copy 0");
    CHECK(objects.json().find("{\"id\": \"1\", \"name\": \"B\", \"state\": \"cancelled\"}") != std::string::npos);
  }
}

TEST_CASE("object cancel: asked in the middle of a block, the block stops at the next line", "[object_cancel]") {
  gcode::Diagnostics diag("test");
  gcode::LayerMarkers markers;
  gcode::Pipeline p(markers);
  gcode::serial::ObjectCancel objects(diag, p.precision());
  objects.add_stage(p, 0);
  gctest::FnStage after([&](const gcode::TrackedLine& t, gcode::Emitter& out) {
    out.pass(t);
    if (t.raw.text == "G1 X60 Y50 E3 F1200") objects.cancel("B");
  });
  p.add(after);
  const std::string out = gctest::run_stages(p, kCancelPlate);
  CHECK(out.find("E3") != std::string::npos);
  CHECK(out.find("G1 X60 Y60 E4") == std::string::npos);
  // A again, primed as in the input: the E coordinate the input has there.
  CHECK(out.find("G1 X0 Y10 E5 F1200") != std::string::npos);
  const std::vector<std::string> listing = objects.listing();
  REQUIRE(listing.size() == 3);
  CHECK(listing[2].find("cancelled after input line 14") != std::string::npos);
}

TEST_CASE("object cancel: a resume reads the printed part, and stands in the object it stopped in", "[object_cancel]") {
  const std::string text = kCancelPlate;
  // Printed up to B's first extrusion; B cancelled by the journal.
  const std::size_t cut = text.find("G1 X60 Y60 E4");
  gcode::serial::PrintedObjects printed;
  printed.feed(text.substr(0, 40));
  printed.feed(text.substr(40, cut - 40));
  gcode::Diagnostics diag("test");
  gcode::LayerMarkers markers;
  gcode::Pipeline p(markers);
  gcode::MachineState at;
  at.apply(gcode::Line::parse("G90"));
  at.apply(gcode::Line::parse("M82"));
  at.apply(gcode::Line::parse("G1 X60 Y50 Z0.2 E3"));
  p.start_from(at);
  gcode::serial::ObjectCancel objects(diag, p.precision());
  objects.continue_from(printed.tracker());
  objects.exclude({"p:B id:1 copy 0"}, "the journal", true);
  objects.add_stage(p, 15);
  const std::string out = gctest::run_stages(p, text.substr(cut));
  INFO(out);
  CHECK(out.find("G1 X60 Y60 E4") == std::string::npos);
  CHECK(out.find("G1 X0 Y10 E5 F1200") != std::string::npos);
  CHECK(objects.listing()[0] == "objects: 2 (PrusaSlicer labels)");
}
