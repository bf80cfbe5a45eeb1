// Keeping some layers (transform/layer_extract.hpp): every layer kept is the
// input byte for byte; left-out layers become a bridge that keeps absolute E
// continuous, restores firmware retraction, lifts above both heights,
// travels, comes down and restores the feed rate; the bridge's lines take
// the input's CRLF even when the input is read in blocks of sixteen bytes
// (the writer owns the ending: no view into a refilled buffer).
#include <catch2/catch.hpp>

#include <functional>
#include <set>
#include <string>

#include "gcode/core/output_buffer.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "gcode/pipeline/writer.hpp"
#include "gcode/transform/layer_extract.hpp"
#include "test_support.hpp"

using gcode::ExtractOptions;
using gcode::LayerExtractor;

namespace {

// Four layers (Z 0.2 .. 0.8) in absolute E; `nl` the line ending.
std::string four_layers(const std::string& nl, bool relative = false) {
  std::string s = std::string(relative ? "M83" : "M82") + nl + "G28" + nl + "G92 E0" + nl;
  const char* layer[] = {
      ";LAYER:0|G1 Z0.2 F600|G1 X10 Y10 F3000|G1 X20 Y10 E1.5 F1200",
      ";LAYER:1|G1 Z0.4 F600|G1 X20 Y20 F3000|G1 X10 Y20 E3.25 F1200",
      ";LAYER:2|G1 Z0.6|G1 X15 Y15|G1 X10 Y10 E4.125",
      ";LAYER:3|G1 Z0.8 F600|G1 X30 Y30 F3000|G1 X40 Y30 E5 F1200",
  };
  for (const char* l : layer) {
    std::string t = l;
    for (std::size_t at; (at = t.find('|')) != std::string::npos;) t.replace(at, 1, nl);
    s += t + nl;
  }
  return s + "M84" + nl;
}

struct Extracted {
  std::string out;
  int written = 0;
};

// The layers in `keep`, read from a file in blocks of `block` bytes.
Extracted extract(const std::string& text, std::set<int> keep, std::size_t block = 1 << 18, ExtractOptions o = {}) {
  std::string path = gctest::temp_dir() + "/in.gcode";
  gctest::write_file(path, text);
  gctest::OpenedFile in(path);
  gcode::LayerMarkers markers;
  gcode::Pipeline pipeline(markers, gcode::PipelineOptions{.layers = true, .block_size = block});
  LayerExtractor extractor([keep](const gcode::LayerInfo& info) { return keep.count(info.index) > 0; },
                           pipeline.precision(), o);
  pipeline.add(extractor);
  Extracted r;
  {
    gcode::OutputBuffer buffer(r.out);
    gcode::GcodeWriter writer(buffer);
    pipeline.add(writer);
    pipeline.run(in.fd());
  }
  r.written = extractor.layers_written();
  return r;
}

std::string lf_to(const std::string& text, const std::string& nl) {
  std::string out;
  for (char c : text) {
    if (c == '\n') {
      out += nl;
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

TEST_CASE("layer extract: every layer kept is the input byte for byte", "[layer_extract]") {
  for (const std::string nl : {"\n", "\r\n"}) {
    Extracted r = extract(four_layers(nl), {1, 2, 3, 4}, 16);
    CHECK(r.out == four_layers(nl));
    CHECK(r.written == 4);
  }
}

TEST_CASE("layer extract: a bridge over left-out layers, CRLF through tiny blocks", "[layer_extract]") {
  const std::string bridged =
      "M82\nG28\nG92 E0\n;LAYER:0\nG1 Z0.2 F600\nG1 X10 Y10 F3000\nG1 X20 Y10 E1.5 F1200\n"
      "; layers 2-3 left out\n"
      "G92 E4.125\n"          // E where the left-out layers ended
      "G0 Z1.6 F600\n"        // 1 mm above the higher of Z 0.2 (printed) and 0.6 (to come)
      "G0 X10 Y10 F3000\n"
      "G0 Z0.6 F600\n"
      "G1 F1200\n"            // the feed rate the next layer expects
      ";LAYER:3\nG1 Z0.8 F600\nG1 X30 Y30 F3000\nG1 X40 Y30 E5 F1200\nM84\n";
  for (const std::string nl : {"\n", "\r\n"}) {
    for (std::size_t block : {std::size_t{16}, std::size_t{17}, std::size_t{1} << 18}) {
      Extracted r = extract(four_layers(nl), {1, 4}, block);
      CHECK(r.out == lf_to(bridged, nl));
      CHECK(r.written == 2);
    }
  }
}

TEST_CASE("layer extract: the bridge's note and speeds are the caller's", "[layer_extract]") {
  ExtractOptions o;
  o.note_prefix = "gc-layers: ";
  o.lift_mm = 0.25;
  o.travel_feedrate = 9000;
  o.z_feedrate = 300;
  Extracted r = extract(four_layers("\n"), {1, 3, 4}, 1 << 18, o);
  std::string expected_bridge = "; gc-layers: layer 2 left out\nG92 E3.25\nG0 Z0.65 F300\nG0 X10 Y20 F9000\nG0 Z0.4 F300\nG1 F1200\n";
  CHECK(r.out.find("G1 X20 Y10 E1.5 F1200\n" + expected_bridge + ";LAYER:2\n") != std::string::npos);
  CHECK(r.written == 3);
}

TEST_CASE("layer extract: relative E needs no G92", "[layer_extract]") {
  Extracted r = extract(four_layers("\n", true), {1, 4});
  CHECK(r.out.find("; layers 2-3 left out\nG0 Z1.6 F600\nG0 X10 Y10 F3000\nG0 Z0.6 F600\nG1 F1200\n;LAYER:3\n") !=
        std::string::npos);
  CHECK(r.out.find("G92 E4") == std::string::npos);
}

TEST_CASE("layer extract: layers left out at the end keep only E continuous", "[layer_extract]") {
  Extracted r = extract(four_layers("\r\n"), {1, 2});
  CHECK(r.out ==
        lf_to("M82\nG28\nG92 E0\n;LAYER:0\nG1 Z0.2 F600\nG1 X10 Y10 F3000\nG1 X20 Y10 E1.5 F1200\n"
              ";LAYER:1\nG1 Z0.4 F600\nG1 X20 Y20 F3000\nG1 X10 Y20 E3.25 F1200\n"
              "; layers 3-4 left out\nG92 E5\nM84\n",
              "\r\n"));
}

TEST_CASE("layer extract: left-out layers at the start travel from the home position", "[layer_extract]") {
  Extracted r = extract(four_layers("\n"), {3});
  CHECK(r.out ==
        "M82\nG28\nG92 E0\n; layers 1-2 left out\nG92 E3.25\nG0 Z1.4 F600\nG0 X10 Y20 F3000\nG0 Z0.4 F600\nG1 F1200\n"
        ";LAYER:2\nG1 Z0.6\nG1 X15 Y15\nG1 X10 Y10 E4.125\n; layer 4 left out\nG92 E5\nM84\n");
  CHECK(r.written == 1);
}

TEST_CASE("layer extract: firmware retraction left on by the skipped layers is restored", "[layer_extract]") {
  std::string text = four_layers("\n");
  // Layer 3 ends retracted by the firmware (G10); layer 4 starts with G11.
  text.replace(text.find(";LAYER:3"), 8, "G10\n;LAYER:3\nG11");
  Extracted r = extract(text, {1, 4});
  CHECK(r.out.find("; layers 2-3 left out\nG92 E4.125\nG10\nG0 Z1.6") != std::string::npos);
}

TEST_CASE("layer extract: positioning modes the left-out layers set are restored", "[layer_extract]") {
  // Layer 3 switches to G91 for good: layer 4 is written for relative moves
  // (and, in Marlin, relative E), so the printer must be told.
  std::string g91 = four_layers("\n");
  g91.replace(g91.find(";LAYER:2\n"), 9, ";LAYER:2\nG91\n");
  Extracted r = extract(g91, {1, 4});
  // No absolute travel; the E coordinate, for the next G90 makes E absolute.
  CHECK(r.out.find("; layers 2-3 left out\nG92 E7.375\nG91\n;LAYER:3\n") != std::string::npos);
  // M83 in a left-out layer: the E mode is restored, no G92 in relative E.
  std::string m83 = four_layers("\n");
  m83.replace(m83.find(";LAYER:2\n"), 9, ";LAYER:2\nM83\n");
  Extracted e = extract(m83, {1, 4});
  CHECK(e.out.find("; layers 2-3 left out\nM83\nG0 Z1.6 F600\nG0 X10 Y10 F3000\n") != std::string::npos);
  // Back to absolute positioning and E at the next layer kept.
  std::string g90 = four_layers("\n");
  g90.replace(g90.find(";LAYER:1\n"), 9, "G91\n;LAYER:1\n");
  g90.replace(g90.find(";LAYER:2\n"), 9, ";LAYER:2\nG90\n");
  Extracted a = extract(g90, {1, 4});
  CHECK(a.out.find("; layers 2-3 left out\nG92 E4.125\nG90\nG0 Z") != std::string::npos);
}

TEST_CASE("layer extract: left-out layers that end in G91 keep E for the G90 after them", "[layer_extract]") {
  // Layer 3 moves in G91 (Marlin: E relative too) and stays there; layer 4
  // goes back to G90 and absolute E: its first extrusion pushes what it does
  // in the whole file.
  std::string text = four_layers("\n");
  text.replace(text.find(";LAYER:2\nG1 Z0.6\nG1 X15 Y15\nG1 X10 Y10 E4.125\n"), 41,
               ";LAYER:2\nG91\nG1 Z0.2\nG1 X5 Y-5\nG1 X-5 Y-5 E0.875\n");
  text.replace(text.find(";LAYER:3\n"), 9, ";LAYER:3\nG90\n");
  auto pushed = [](const std::string& gcode, const std::string& at) {
    gcode::MachineState s;
    gcode::MemoryLineSplitter split(gcode);
    gcode::RawLine raw;
    while (split.next(raw)) {
      gcode::Move m = s.apply(gcode::Line::parse(raw.text));
      if (raw.text == at) return m.filament;
    }
    FAIL("no line " << at);
    return 0.0;
  };
  Extracted r = extract(text, {1, 4});
  INFO(r.out);
  CHECK(pushed(r.out, "G1 X40 Y30 E5 F1200") == Approx(pushed(text, "G1 X40 Y30 E5 F1200")));
  CHECK(pushed(text, "G1 X40 Y30 E5 F1200") == Approx(0.875));
}

TEST_CASE("layer extract: temperatures and the fan the left-out layers set are restored", "[layer_extract]") {
  std::string text = four_layers("\n");
  text.replace(text.find("M82\n"), 4, "M82\nM104 S215\nM140 S60\n");
  // Cura turns the fan on at layer 2; a tower lowers the temperature at 3.
  text.replace(text.find(";LAYER:1\n"), 9, ";LAYER:1\nM106 S255\n");
  text.replace(text.find(";LAYER:2\n"), 9, ";LAYER:2\nM104 S205\nM140 S55\nM106 S127.5\n");
  Extracted r = extract(text, {1, 4});
  CHECK(r.out.find("; layers 2-3 left out\nG92 E4.125\nM104 S205\nM140 S55\nM106 S127.5\nG0 Z1.6 F600\n") !=
        std::string::npos);
  // Only what differs: layer 3 kept, the fan and heat it set are printed.
  Extracted three = extract(text, {1, 3, 4});
  CHECK(three.out.find("; layer 2 left out\nG92 E3.25\nM106 S255\nG0 Z1.4") != std::string::npos);
  // The fan off again.
  std::string off = four_layers("\n");
  off.replace(off.find(";LAYER:0\n"), 9, ";LAYER:0\nM106 S200\n");
  off.replace(off.find(";LAYER:1\n"), 9, ";LAYER:1\nM107\n");
  CHECK(extract(off, {1, 3, 4}).out.find("; layer 2 left out\nG92 E3.25\nM107\nG0 Z") != std::string::npos);
  // Another tool's temperature names its tool.
  std::string t1 = four_layers("\n");
  t1.replace(t1.find(";LAYER:1\n"), 9, ";LAYER:1\nM104 T1 S190\n");
  CHECK(extract(t1, {1, 3, 4}).out.find("; layer 2 left out\nG92 E3.25\nM104 T1 S190\nG0 Z") != std::string::npos);
}
