#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "gcode/core/layer_tracker.hpp"

namespace {

struct Recorded {
  std::vector<gcode::LayerInfo> layers;
  std::vector<std::string> lines;        // text in emission order
  std::vector<int> line_layer;           // layer of each line (0 start, -1 end)
  std::uint64_t end_code_line = 0;
  bool saw_end = false;
};

struct Recorder : gcode::LayerSink {
  Recorded r;
  void on_layer(const gcode::LayerInfo& l, const gcode::MachineState&) override { r.layers.push_back(l); }
  void on_end_code(std::uint64_t line, std::uint64_t, const gcode::MachineState&) override {
    r.saw_end = true;
    r.end_code_line = line;
  }
  void on_line(const gcode::TrackedLine& t) override {
    r.lines.emplace_back(t.raw.text);
    r.line_layer.push_back(t.region == gcode::Region::EndCode ? -1 : t.layer);
  }
};

Recorded track(const std::string& text, const std::string& pattern = "") {
  Recorder rec;
  gcode::LayerMarkers markers = pattern.empty() ? gcode::LayerMarkers() : gcode::LayerMarkers(pattern);
  gcode::LayerTracker tracker(rec, markers);
  gcode::MemoryLineSplitter split(text);
  gcode::RawLine raw;
  while (split.next(raw)) tracker.push(raw);
  tracker.finish();
  return rec.r;
}

int layer_of(const Recorded& r, const std::string& line) {
  for (std::size_t i = 0; i < r.lines.size(); ++i)
    if (r.lines[i] == line) return r.line_layer[i];
  return -99;
}

}  // namespace

TEST_CASE("every line comes out once, in order", "[layer_tracker][property]") {
  std::string text = "G28\nG1 Z0.2\nG1 X10 E1\nG1 Z0.4\nG1 X0 E2\nG1 Z10\nM84";
  Recorded r = track(text);
  std::string joined;
  for (auto& l : r.lines) joined += l + "\n";
  CHECK(joined == text + "\n");
}

TEST_CASE("unmarked files: a layer starts at extrusion on a new Z, hops do not count", "[layer_tracker]") {
  // Slic3r's start code purges at Z 0.3 before a 0.2 mm first layer: a first
  // extrusion height above the next is start code (the slicer counts no layer there).
  std::string text =
      "G28\nG1 Z5 F600\nG1 Z0.3\nG1 X0 Y0\nG1 X50 E3 ; purge\n"
      "G1 Z0.2\nG1 X10 Y10\nG1 X20 E4\nG1 E3.2 ; retract\nG1 Z0.6 ; hop\nG1 X30\nG1 Z0.2\nG1 E4\nG1 X40 E5\n"
      "G1 E4.2\nG1 Z0.4\nG1 X10\nG1 X20 E6\nG1 E5\nG1 Z10\nM104 S0\n";
  Recorded r = track(text);
  REQUIRE(r.layers.size() == 2);
  CHECK(r.layers[0].z == Approx(0.2));
  CHECK(r.layers[1].z == Approx(0.4));
  CHECK(layer_of(r, "G1 Z0.3") == 0);
  CHECK(layer_of(r, "G1 X50 E3 ; purge") == 0);
  CHECK(layer_of(r, "G1 Z0.2") == 1);      // the move down to the first layer belongs to it
  CHECK(layer_of(r, "G1 Z5 F600") == 0);
  CHECK(layer_of(r, "G1 Z0.6 ; hop") == 1);
  CHECK(layer_of(r, "G1 E4.2") == 1);      // retract after the last extrusion stays in its layer
  CHECK(layer_of(r, "G1 Z0.4") == 2);
  CHECK(layer_of(r, "G1 E5") == -1);       // end code starts after the last extrusion
  CHECK(layer_of(r, "M104 S0") == -1);
  CHECK(r.saw_end);
}

TEST_CASE("Cura: the move to the next Z before the LAYER:n marker belongs to the new layer", "[layer_tracker]") {
  std::string text =
      "M82\nG92 E0\nG1 F1500 E-6.5\n;LAYER_COUNT:2\n;LAYER:0\nG0 F600 X10 Y10 Z0.3\nG1 F1200 X20 E1\n"
      "G1 F2700 E-5\n;MESH:NONMESH\nG0 F600 X10 Y10 Z0.5\n;TIME_ELAPSED:1\n;LAYER:1\nG0 X12\nG1 F2700 E1\n"
      "G1 X20 E2\n;TIME_ELAPSED:2\nG1 F2700 E-3\nM104 S0\n";
  Recorded r = track(text);
  REQUIRE(r.layers.size() == 2);
  CHECK(r.layers[0].slicer_number == 0);
  CHECK(r.layers[1].slicer_number == 1);
  CHECK(r.layers[1].z == Approx(0.5));
  CHECK(layer_of(r, "G1 F2700 E-5") == 1);
  CHECK(layer_of(r, ";MESH:NONMESH") == 1);
  CHECK(layer_of(r, "G0 F600 X10 Y10 Z0.5") == 2);
  CHECK(layer_of(r, ";LAYER:1") == 2);
  CHECK(layer_of(r, ";TIME_ELAPSED:2") == -1);
}

TEST_CASE("PrusaSlicer: LAYER_CHANGE with Z: and HEIGHT: comments, purge before is start code", "[layer_tracker]") {
  std::string text =
      "M83\nG1 Z0.2\nG1 X60 E9 ; intro line\nG1 X100 E12.5 ; intro line\nG92 E0\n"
      ";LAYER_CHANGE\n;Z:0.2\n;HEIGHT:0.2\nG1 E-.8\nG1 Z.2\nG1 X10 Y10\nG1 E.8\nG1 X20 E1\n"
      ";LAYER_CHANGE\n;Z:0.4\n;HEIGHT:0.2\n;LAYER:1\nG1 E-.8\nG1 Z.6\nG1 X10\nG1 Z.4\nG1 E.8\nG1 X20 E1\n"
      ";LAYER_CHANGE\n;Z:0.6\n;HEIGHT:0.2\n;LAYER_CHANGE\n;Z:0.8\n;HEIGHT:0.2\nG1 Z.8\nG1 X30 E1\nG1 E-1\n";
  Recorded r = track(text);
  REQUIRE(r.layers.size() == 4);  // ;LAYER:1 after ;LAYER_CHANGE is the same layer; 0.6 is empty
  CHECK(layer_of(r, "G1 X60 E9 ; intro line") == 0);
  CHECK(r.layers[1].z == Approx(0.4));
  CHECK(r.layers[1].slicer_number == 1);
  CHECK(r.layers[2].empty);
  CHECK(r.layers[2].z == Approx(0.6));
  CHECK(r.layers[3].z == Approx(0.8));
  CHECK(r.layers[3].height == Approx(0.2));
}

TEST_CASE("vase mode: with markers, rising Z inside extrusion starts no layer", "[layer_tracker]") {
  std::string text = ";LAYER:0\nG1 Z0.2\nG1 X10 E1\n;LAYER:1\nG1 X20 Z0.25 E2\nG1 X30 Z0.3 E3\nG1 X40 Z0.35 E4\n";
  Recorded r = track(text);
  CHECK(r.layers.size() == 2);
}

TEST_CASE("unmarked vase: the spiral wall has one layer per layer height of climb", "[layer_tracker]") {
  // Two solid layers of 0.2 mm, then a wall climbing 0.1 mm per move: its
  // turns are layers 3, 4 and 5, each ending one layer height higher, and a
  // turn starts with the first move whose end passes the previous turn's top.
  std::string text = "G1 Z0.2\nG1 X10 E1\nG1 Z0.4\nG1 X0 E2\n";
  for (int i = 1; i <= 6; ++i) text += "G1 Z" + std::to_string(0.4 + 0.1 * i).substr(0, 3) + " X" + (i % 2 ? "10" : "0") + " E" + std::to_string(2 + i) + "\n";
  Recorded r = track(text);
  REQUIRE(r.layers.size() == 5);
  CHECK(r.layers[2].z == Approx(0.6));
  CHECK(r.layers[3].z == Approx(0.8));
  CHECK(r.layers[4].z == Approx(1.0));
  CHECK(r.layers[4].height == Approx(0.2));
  CHECK(layer_of(r, "G1 Z0.5 X10 E3") == 3);
  CHECK(layer_of(r, "G1 Z0.6 X0 E4") == 3);
  CHECK(layer_of(r, "G1 Z0.7 X10 E5") == 4);
  CHECK(layer_of(r, "G1 Z1.0 X0 E8") == 5);
  // A single climbing move inside the first turn is still that turn.
  CHECK(track("G1 Z0.2\nG1 X10 E1\nG1 Z0.4\nG1 X0 E2\nG1 Z0.402 X10 E3\nG1 Z0.404 X0 E4\n").layers.size() == 3);
}

TEST_CASE("Simplify3D, Orca and user markers", "[layer_tracker]") {
  CHECK(track("; layer 1, Z = 0.200\nG1 Z0.2\nG1 X1 E1\n; layer 2, Z = 0.400\nG1 Z0.4\nG1 X2 E2\n").layers.size() == 2);
  Recorded orca = track("; CHANGE_LAYER\n; Z_HEIGHT: 0.2\nG1 Z.2\nG1 X1 E1\n; CHANGE_LAYER\n; Z_HEIGHT: 0.4\nG1 X2 E2\n");
  REQUIRE(orca.layers.size() == 2);
  CHECK(orca.layers[1].z == Approx(0.4));
  Recorded user = track(";NEXT 7\nG1 Z.2\nG1 X1 E1\n;NEXT 8\nG1 X2 E2\n", "^NEXT (\\d+)");
  REQUIRE(user.layers.size() == 2);
  CHECK(user.layers[1].slicer_number == 8);
  CHECK_THROWS_AS(gcode::LayerMarkers("(unclosed"), std::invalid_argument);
}

TEST_CASE("no extrusion: everything is start code, no crash", "[layer_tracker]") {
  Recorded r = track("G28\nG1 Z10\nM84\n");
  CHECK(r.layers.empty());
  CHECK(r.lines.size() == 3);
  CHECK(track("").lines.empty());
}

TEST_CASE("the state a sink gets at a boundary is the state before the layer's first line", "[layer_tracker]") {
  // Every layer change here is a bare Z move right after an extrusion, so the
  // boundary is the first held line; the fourth one is decided after the
  // tracker left its undecided phase (a different code path).
  struct BeforeZ : gcode::LayerSink {
    std::vector<double> before_z, first_start_z;
    bool pending = false;
    void on_layer(const gcode::LayerInfo&, const gcode::MachineState& before) override {
      before_z.push_back(before.position[gcode::kZ]);
      pending = true;
    }
    void on_line(const gcode::TrackedLine& t) override {
      if (pending) first_start_z.push_back(t.move.start[gcode::kZ]);
      pending = false;
    }
  } sink;
  std::string text =
      "G28\nG1 Z0.2\nG1 X10 E1\nG1 X20 E2\nG1 Z0.4\nG1 X10 E3\nG1 Z0.6\nG1 X20 E4\nG1 Z0.8\nG1 X30 E5\n"
      "G1 Z1.0\nG1 X40 E6\n";
  gcode::LayerMarkers markers;
  gcode::LayerTracker tracker(sink, markers);
  gcode::MemoryLineSplitter split(text);
  gcode::RawLine raw;
  while (split.next(raw)) tracker.push(raw);
  tracker.finish();
  REQUIRE(sink.before_z.size() == 5);
  CHECK(sink.before_z == sink.first_start_z);
  CHECK(sink.before_z.back() == Approx(0.8));
}

TEST_CASE("a stream resumed inside a layer, its mode decided: each extrusion comes out at once, not at the next marker",
          "[layer_tracker]") {
  // gc-send's resume: the lines from mid-layer 3 to the next marker. Left to
  // find out the kind of file, the tracker held all of them until the
  // marker (the sender then numbered a layer's worth at once).
  std::string text = "G1 X10 Y10 E0.5\nG1 X20 Y10 E0.5\nG1 E-0.8\nG1 X30 Y30\nG1 E0.8\nG1 X40 Y30 E0.5\n"
                     ";LAYER_CHANGE\n;Z:0.8\nG1 Z0.8\nG1 X50 Y30 E0.5\n";
  gcode::LayerMarkers markers;
  for (gcode::LayerMode mode : {gcode::LayerMode::Undecided, gcode::LayerMode::Markers}) {
    INFO("mode " << static_cast<int>(mode));
    struct Counter : gcode::LayerSink {
      std::size_t pushed = 0;
      std::vector<std::size_t> out_at;  // lines pushed when each line came out
      void on_layer(const gcode::LayerInfo&, const gcode::MachineState&) override {}
      void on_end_code(std::uint64_t, std::uint64_t, const gcode::MachineState&) override {}
      void on_line(const gcode::TrackedLine&) override { out_at.push_back(pushed); }
    } sink;
    gcode::LayerTracker tracker(sink, markers);
    gcode::MachineState state;
    state.relative_e = true;
    tracker.start_from(state);
    if (mode != gcode::LayerMode::Undecided) tracker.decide_mode(mode);
    gcode::MemoryLineSplitter split(text);
    gcode::RawLine raw;
    while (split.next(raw)) {
      ++sink.pushed;
      tracker.push(raw);
    }
    tracker.finish();
    REQUIRE(sink.out_at.size() == 10);
    if (mode == gcode::LayerMode::Undecided) {
      CHECK(sink.out_at[0] >= 7);  // held to the marker
    } else {
      CHECK(sink.out_at[0] == 1);  // the first extrusion at once
      CHECK(sink.out_at[1] == 2);
      CHECK(sink.out_at[5] == 6);  // the travel between waits for the next extrusion only
    }
  }
}

TEST_CASE("layer marker search: a marker found in blocks cut anywhere, or none", "[layer_tracker]") {
  gcode::LayerMarkers markers;
  const std::string marked = "G1 X1 E1 ; a comment\nG1 X2\r\n;LAYER_CHANGE\r\nG1 X3\n";
  for (std::size_t cut = 0; cut <= marked.size(); ++cut) {
    INFO("cut at " << cut);
    gcode::LayerMarkerSearch search(markers);
    search.feed(std::string_view(marked).substr(0, cut));
    search.feed(std::string_view(marked).substr(cut));
    search.feed("\n");
    CHECK(search.found());
  }
  gcode::LayerMarkerSearch none(markers);
  none.feed("G1 X1 E1 ; LAYER_CHANGE is only named here\nG1 Z0.4 ; move up\n");
  none.feed(std::string(100000, 'x'));  // a huge line without an end is no marker
  none.feed(";LAYER_CHANGE\n");          // ... nor is what follows it on that line
  CHECK_FALSE(none.found());
  gcode::LayerMarkerSearch slic3r(markers);
  slic3r.feed("G1 Z0.6 F9000 ; move to next layer (2)\n");
  CHECK(slic3r.found());
}
