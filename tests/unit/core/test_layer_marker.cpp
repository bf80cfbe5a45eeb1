// Layer-marker comments as slicers write them (tests/fixtures/sources/
// layer-markers.md names the source of each example line), read through
// Line::parse as the tracker reads them.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "gcode/core/layer_marker.hpp"
#include "gcode/core/line.hpp"
#include "gcode/core/line_reader.hpp"
#include "test_support.hpp"

using gcode::CommentInfo;
using gcode::LayerMarkers;
using gcode::MarkerKind;

namespace {

CommentInfo comment_line(const std::string& text, const LayerMarkers& markers = LayerMarkers()) {
  gcode::Line line = gcode::Line::parse(text);
  REQUIRE(line.kind == gcode::CommandKind::None);
  return markers.classify(line.comment_text());
}

CommentInfo move_line(const std::string& text, const LayerMarkers& markers = LayerMarkers()) {
  gcode::Line line = gcode::Line::parse(text);
  REQUIRE(line.is_move());
  return markers.classify_move(line.comment_text());
}

}  // namespace

TEST_CASE("Cura and ideaMaker and MatterSlice layer numbers from 0 and negative for rafts", "[layer_marker]") {
  CommentInfo c = comment_line(";LAYER:0");
  CHECK(c.marker == MarkerKind::CuraLayer);
  CHECK(c.has_number);
  CHECK(c.number == 0);
  CHECK_FALSE(c.has_z);
  c = comment_line(";LAYER:-2");  // CuraEngine 15 raft, ideaMaker raft
  CHECK(c.marker == MarkerKind::CuraLayer);
  CHECK(c.number == -2);
  c = comment_line("; LAYER:-3");  // MatterSlice raft base
  CHECK(c.marker == MarkerKind::CuraLayer);
  CHECK(c.number == -3);
  // A number no layer has is no number (and no undefined conversion to long).
  CHECK_FALSE(comment_line(";LAYER:1e300").has_number);
  CHECK_FALSE(comment_line(";; --- layer 99999999999999999999 (0.2 @ 0.4) ---").has_number);
  // Header lines that name layers are not markers.
  CHECK(comment_line(";LAYER_COUNT:100").marker == MarkerKind::None);
  CHECK(comment_line(";Layer count: 299").marker == MarkerKind::None);
  CHECK(comment_line(";Layer height: 0.2").marker == MarkerKind::None);
  CHECK_FALSE(comment_line(";Layer height: 0.2").has_height);
}

TEST_CASE("PrusaSlicer LAYER_CHANGE with its Z and HEIGHT lines", "[layer_marker]") {
  CHECK(comment_line(";LAYER_CHANGE").marker == MarkerKind::LayerChange);
  CommentInfo z = comment_line(";Z:0.2");
  CHECK(z.marker == MarkerKind::None);
  CHECK(z.has_z);
  CHECK(z.z == 0.2);
  CommentInfo h = comment_line(";HEIGHT:0.07");
  CHECK(h.has_height);
  CHECK(h.height == 0.07);
}

TEST_CASE("BambuStudio and Orca CHANGE_LAYER with Z_HEIGHT and LAYER_HEIGHT", "[layer_marker]") {
  CHECK(comment_line("; CHANGE_LAYER").marker == MarkerKind::ChangeLayer);
  CommentInfo z = comment_line("; Z_HEIGHT: 0.4");
  CHECK(z.has_z);
  CHECK(z.z == 0.4);
  CommentInfo h = comment_line("; LAYER_HEIGHT: 0.28");
  CHECK(h.has_height);
  CHECK(h.height == 0.28);
  // The 1-based progress line after the marker is not a second marker.
  CommentInfo progress = comment_line("; layer num/total_layer_count: 2/30");
  CHECK(progress.marker == MarkerKind::None);
  CHECK_FALSE(progress.has_number);
}

TEST_CASE("Simplify3D layer N from 1 with its Z", "[layer_marker]") {
  CommentInfo c = comment_line("; layer 3, Z = 0.600");
  CHECK(c.marker == MarkerKind::Simplify3D);
  CHECK(c.number == 3);
  CHECK(c.z == 0.6);
  CHECK(comment_line("; layer end").marker == MarkerKind::None);
  CHECK(comment_line("; layer 3 of 40").marker == MarkerKind::None);
}

TEST_CASE("KISSlicer BEGIN_LAYER_OBJECT with z and z_thickness and the old form with z only", "[layer_marker]") {
  CommentInfo c = comment_line("; BEGIN_LAYER_OBJECT z=0.300 z_thickness=0.100");
  CHECK(c.marker == MarkerKind::KISSlicer);
  CHECK_FALSE(c.has_number);
  CHECK(c.has_z);
  CHECK(c.z == 0.3);
  CHECK(c.has_height);
  CHECK(c.height == 0.1);
  CommentInfo old = comment_line("; BEGIN_LAYER_OBJECT z=0.55");  // KISSlicer 1.1
  CHECK(old.marker == MarkerKind::KISSlicer);
  CHECK(old.z == 0.55);
  CHECK_FALSE(old.has_height);
  CHECK(comment_line("; END_LAYER_OBJECT z=0.263").marker == MarkerKind::None);
}

TEST_CASE("Kiri:Moto layer N from 0 with height and Z", "[layer_marker]") {
  CommentInfo c = comment_line(";; --- layer 12 (0.200 @ 2.65) ---");
  CHECK(c.marker == MarkerKind::KiriMoto);
  CHECK(c.number == 12);
  CHECK(c.height == 0.2);
  CHECK(c.z == 2.65);
  CommentInfo first = comment_line(";; --- layer 0 (0.250 @ 0.25) ---");
  CHECK(first.number == 0);
  CHECK(first.z == 0.25);
  // Its other ";;" comments are not markers.
  CHECK(comment_line(";; --- print time: 200s ---").marker == MarkerKind::None);
  CHECK(comment_line(";; ---").marker == MarkerKind::None);
}

// Line::parse does not yet return a comment for a line that is only a
// parenthesised comment (it marks it malformed), so these are classified from
// the text inside the parentheses, as Line::comment_text gives it for "(...)".
TEST_CASE("Skeinforge layer tags and Miracle-Grue slices in parentheses", "[layer_marker]") {
  LayerMarkers markers;
  CommentInfo s = markers.classify("<layer> 0.832");  // (<layer> 0.832 )
  CHECK(s.marker == MarkerKind::Skeinforge);
  CHECK(s.z == 0.832);
  CHECK(markers.classify("</layer>").marker == MarkerKind::None);
  CHECK(markers.classify("<layerThickness> 0.27 </layerThickness>").marker == MarkerKind::None);
  CommentInfo m = markers.classify("Slice 2, 1 Extruder");  // (Slice 2, 1 Extruder)
  CHECK(m.marker == MarkerKind::MiracleGrue);
  CHECK(m.number == 2);
  CHECK(markers.classify("Layer Height: \t0.270").marker == MarkerKind::None);
  CHECK(comment_line("; Slicer settings").marker == MarkerKind::None);
}

TEST_CASE("Slic3r verbose move to next layer gives the 0-based number", "[layer_marker]") {
  CommentInfo c = move_line("G1 Z0.200 F9000.000 ; move to next layer (0)");
  CHECK(c.marker == MarkerKind::LayerMove);
  CHECK(c.has_number);
  CHECK(c.number == 0);
  CHECK(move_line("G1 Z35.800 F9000.000 ; move to next layer (179)").number == 179);
  CHECK(move_line("G1 Z.6 F720 ; move to next layer (2)").number == 2);  // PrusaSlicer 2.5
  CommentInfo old = move_line("G1 Z1.400 F9000.000 ; move to next layer");  // Slic3r 0.9
  CHECK(old.marker == MarkerKind::LayerMove);
  CHECK_FALSE(old.has_number);
  // Other verbose comments on moves are not markers.
  CHECK(move_line("G1 X101.150 Y101.247 F9000.000 ; move to first skirt point").marker == MarkerKind::None);
  CHECK(move_line("G1 X102.848 Y100.073 E4.06473 ; skirt").marker == MarkerKind::None);
  CHECK(move_line("G1 Z.4 F720 ; restore layer Z").marker == MarkerKind::None);
  CHECK(move_line("G1 X10 Y10").marker == MarkerKind::None);
}

TEST_CASE("the verbose moves of the Slic3r fixtures number their layers 0 to n-1", "[layer_marker][fixtures]") {
  struct Case {
    const char* fixture;
    long markers;
  };
  for (Case k : {Case{"slic3r_cube_0.2_verbose_abs_purge.gcode", 25}, Case{"slic3r_vase_0.2_spiral_verbose.gcode", 180},
                 Case{"slic3r_tshape_0.2_support_verbose.gcode", 81}}) {
    INFO(k.fixture);
    std::string text = gctest::read_file(gctest::fixture_path(k.fixture));
    LayerMarkers markers;
    gcode::MemoryLineSplitter split(text);
    gcode::RawLine raw;
    long next = 0, comment_markers = 0;
    while (split.next(raw)) {
      gcode::Line line = gcode::Line::parse(raw.text);
      if (line.comment.empty()) continue;
      if (line.kind == gcode::CommandKind::None) {
        comment_markers += markers.classify(line.comment_text()).marker != MarkerKind::None ? 1 : 0;
        continue;
      }
      CommentInfo c = markers.classify_move(line.comment_text());
      if (c.marker == MarkerKind::None) continue;
      REQUIRE(line.is_g(1));
      REQUIRE(line.has('Z'));
      REQUIRE(c.has_number);
      CHECK(c.number == next++);
    }
    CHECK(next == k.markers);
    CHECK(comment_markers == 0);  // nothing else in these files looks like a marker
  }
}

TEST_CASE("a user pattern replaces every built-in marker", "[layer_marker]") {
  LayerMarkers user("^MYLAYER ([0-9]+)");
  CommentInfo c = comment_line("; MYLAYER 7", user);
  CHECK(c.marker == MarkerKind::User);
  CHECK(c.number == 7);
  for (const char* line : {";LAYER:3", ";LAYER_CHANGE", "; CHANGE_LAYER", "; layer 3, Z = 0.600",
                           "; BEGIN_LAYER_OBJECT z=0.3", ";; --- layer 1 (0.2 @ 0.4) ---"}) {
    INFO(line);
    CHECK(comment_line(line, user).marker == MarkerKind::None);
  }
  CHECK(user.classify("<layer> 0.4").marker == MarkerKind::None);
  CHECK(user.classify("Slice 0, 1 Extruder").marker == MarkerKind::None);
  CHECK(move_line("G1 Z0.200 F9000.000 ; move to next layer (0)", user).marker == MarkerKind::None);
  // Heights, Z and feature types still come through.
  CHECK(comment_line(";Z:0.4", user).has_z);
  CHECK(comment_line(";TYPE:Perimeter", user).is_type);
}
