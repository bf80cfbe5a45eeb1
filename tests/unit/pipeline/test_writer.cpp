// The output conventions (pipeline/writer.hpp): unchanged lines byte for
// byte, a changed line with its own ending (and its comment, through
// LineEdit), added lines with the input's ending, the line ending a missing
// final newline needs once something follows it.
#include <catch2/catch.hpp>

#include <functional>
#include <string>

#include "gcode/core/line_edit.hpp"
#include "gcode/core/output_buffer.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "gcode/pipeline/writer.hpp"
#include "fn_stage.hpp"
#include "test_support.hpp"

using gcode::Emitter;
using gcode::Stage;
using gcode::TrackedLine;
using gctest::FnStage;

namespace {

void pass(const TrackedLine& t, Emitter& out) { out.pass(t); }

}  // namespace

TEST_CASE("writer: unchanged lines come out byte for byte", "[writer]") {
  for (const char* text : {"G1  x1.000 Y2 ;  Comment \r\nM104 S200\n", "G28\nG1 X1", "\n\n\r\n", "",
                           "; only a comment", "G1 X1\r\n\rG1 X2\n", "N1 G1 X1*57\n;\xff\xfe binary\n"}) {
    CHECK(gctest::run_stages(text, {}, false) == text);
    CHECK(gctest::run_stages(text, {}, true) == text);
  }
}

TEST_CASE("writer: added lines take the input's line ending", "[writer]") {
  FnStage add([](const TrackedLine& t, Emitter& out) {
    out.pass(t);
    if (t.raw.number == 2) out.insert("M117 added");
  });
  CHECK(gctest::run_stages("G28\r\nG1 X1\r\nG1 X2\r\n", {&add}, false) == "G28\r\nG1 X1\r\nM117 added\r\nG1 X2\r\n");
  CHECK(gctest::run_stages("G28\nG1 X1\nG1 X2\n", {&add}, false) == "G28\nG1 X1\nM117 added\nG1 X2\n");
  // The latest input line decides (a file that mixes them).
  CHECK(gctest::run_stages("G28\nG1 X1\r\nG1 X2\n", {&add}, false) == "G28\nG1 X1\r\nM117 added\r\nG1 X2\n");
}

TEST_CASE("writer: lines added before the first input line wait for its ending", "[writer]") {
  FnStage add([](const TrackedLine& t, Emitter& out) {
    if (t.raw.number == 1) out.insert_lines("; first\n; second");
    out.pass(t);
  });
  CHECK(gctest::run_stages("G28\r\nG1 X1\r\n", {&add}, false) == "; first\r\n; second\r\nG28\r\nG1 X1\r\n");
  CHECK(gctest::run_stages("G28\nG1 X1\r\n", {&add}, false) == "; first\n; second\nG28\nG1 X1\r\n");
  // A first line without an ending says nothing: a newline.
  CHECK(gctest::run_stages("G28", {&add}, false) == "; first\n; second\nG28");
  // A changed first line keeps the input's ending, which it shows.
  FnStage change([](const TrackedLine& t, Emitter& out) {
    if (t.raw.number == 1) {
      out.insert("; first");
      return out.replace(t, "G28 X");
    }
    out.pass(t);
  });
  CHECK(gctest::run_stages("G28\r\nG1 X1\r\n", {&change}, false) == "; first\r\nG28 X\r\nG1 X1\r\n");
  // Nothing but added lines (an empty input): a newline each.
  FnStage only(pass, [](Emitter& out) { out.insert_lines("M84\nM300"); });
  CHECK(gctest::run_stages("", {&only}, false) == "M84\nM300\n");
}

TEST_CASE("writer: a changed line keeps its own ending and, through LineEdit, its comment", "[writer]") {
  FnStage edit([](const TrackedLine& t, Emitter& out) {
    if (!t.line.is_g(1)) return out.pass(t);
    gcode::LineEdit e(t.line);
    e.set('X', gcode::Fixed::from_int(5), 3);
    out.replace(t, e.text());
  });
  CHECK(gctest::run_stages("G1 X1.25 Y2 ; outer wall\r\nG1  X2\nM84", {&edit}, false) ==
        "G1 X5 Y2 ; outer wall\r\nG1  X5\nM84");
  CHECK(gctest::run_stages("G28\nG1 X1 ; last, no newline", {&edit}, false) == "G28\nG1 X5 ; last, no newline");
}

TEST_CASE("writer: a line after an input line without a newline gets the ending it needs", "[writer]") {
  FnStage at_end(pass, [](Emitter& out) { out.insert("M84"); });
  CHECK(gctest::run_stages("G28\nG1 X1", {&at_end}, false) == "G28\nG1 X1\nM84\n");
  CHECK(gctest::run_stages("G28\r\nG1 X1", {&at_end}, false) == "G28\r\nG1 X1\r\nM84\r\n");
  CHECK(gctest::run_stages("G1 X1", {&at_end}, false) == "G1 X1\nM84\n");
  CHECK(gctest::run_stages("", {&at_end}, false) == "M84\n");
}

TEST_CASE("writer: counts the lines it wrote and reports the ending it learnt", "[writer]") {
  std::string out;
  gcode::LayerMarkers markers;
  gcode::Pipeline pipeline(markers, gcode::PipelineOptions{.layers = false});
  FnStage add([](const TrackedLine& t, Emitter& e) {
    e.insert("; x");
    e.pass(t);
  });
  gcode::OutputBuffer buffer(out);
  gcode::GcodeWriter writer(buffer);
  CHECK(writer.ending() == "\n");
  pipeline.add(add);
  pipeline.add(writer);
  pipeline.run_text("G28\r\nG1 X1\r\n");
  buffer.flush();
  CHECK(writer.lines_written() == 4);
  CHECK(writer.ending() == "\r\n");
  CHECK(out == "; x\r\nG28\r\n; x\r\nG1 X1\r\n");
  CHECK_FALSE(writer.reads_state());
  CHECK_FALSE(writer.reads_lines());
}
