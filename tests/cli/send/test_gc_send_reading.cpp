// gc-send reads its input as every tool that reads G-code does: with
// --layer-marker its layers are the user's (the progress counts them and a
// pause comes at their end), and --e-mode decides how a file that never
// says M82/M83 is read, which is what a pause's return writes. The oracle
// is the library's own pipeline over the same text, read each way.
#include <catch2/catch.hpp>

#include <map>
#include <string>
#include <vector>

#include "gcode/core/layer_marker.hpp"
#include "gcode/core/line.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "control_run.hpp"
#include "serial_check.hpp"
#include "test_support.hpp"

using gctest::Checked;
using gctest::PauseRun;
using gctest::number_after;
using gctest::send_with_control;

namespace {

constexpr const char* kCubeFixture = "prusa_cube_0.2_mk3s_rel_zhop.gcode";
// Moves take their time (at 50 times the speed): layer 1 lasts long enough
// for the script to see it begin.
constexpr const char* kVirtualSpec = "time-scale=50,heat-rate=1000";
// Once a layer runs, pause (the rest of the layer, then park), then resume;
// the status file while paused and at the end go to standard output.
constexpr const char* kPauseInALayer =
    "for i in $(seq 1000); do grep -q '\"layer\": [1-9]' \"$S\" 2>/dev/null && break; sleep 0.01; done\n"
    "echo pause > \"$F\"; paused; P=$(cat \"$S\"); echo resume > \"$F\"\n"
    "wait $p; s=$?; echo \"$P\"; cat \"$S\"; exit $s";

// The fixture's start code and its first `layers` layers, each line through
// `keep` (false: left out) before it is written.
template <class Keep>
std::string fixture_layers(int layers, Keep keep) {
  std::string text = gctest::read_file(gctest::fixture_path(kCubeFixture)), out;
  gcode::MemoryLineSplitter split(text);
  gcode::RawLine raw;
  int layer = 0;
  while (split.next(raw)) {
    std::string line(raw.text);
    if (line == ";LAYER_CHANGE" && ++layer > layers) break;
    if (keep(line, layer)) out += line + "\n";
  }
  return out;
}

// The layer of every input line as the library reads `text` with `markers`.
std::map<std::uint64_t, int> layers_of(const std::string& text, const gcode::LayerMarkers& markers) {
  struct Collect : gcode::Stage {
    std::map<std::uint64_t, int> layer;
    void line(const gcode::TrackedLine& t, gcode::Emitter& out) override {
      layer[t.raw.number] = t.layer;
      out.pass(t);
    }
  } collect;
  gcode::Pipeline p(markers);
  p.add(collect);
  p.run_text(text);
  return collect.layer;
}

int layer_count(const std::string& text, const gcode::LayerMarkers& markers) {
  gcode::Pipeline p(markers);
  p.run_text(text);
  return p.tracker().layer_count();
}

}  // namespace

TEST_CASE("gc-send --layer-marker: the layers gc-send counts and pauses at are the user's markers",
          "[gc-send][reading]") {
  // Six layers, but only every second layer change marked, by a comment no
  // slicer writes: by Z there are six layers, by the marker three.
  std::string text = fixture_layers(6, [](std::string& line, int layer) {
    if (line != ";LAYER_CHANGE") return true;
    line = ";PLY";
    return layer % 2 == 1;
  });
  std::string file = gctest::temp_dir() + "/ply.gcode";
  gctest::write_file(file, text);
  const gcode::LayerMarkers by_z, by_ply("^PLY");
  const int z_layers = layer_count(text, by_z), ply_layers = layer_count(text, by_ply);
  REQUIRE(z_layers == 6);
  REQUIRE(ply_layers == 3);
  auto z_layer = layers_of(text, by_z), ply_layer = layers_of(text, by_ply);
  auto input = gctest::commands_of(text);

  for (bool marked : {false, true}) {
    INFO((marked ? "--layer-marker ^PLY" : "the built-in markers"));
    PauseRun r = send_with_control(file, kVirtualSpec, marked ? "--no-pace --layer-marker '^PLY'" : "--no-pace",
                                   kPauseInALayer);
    INFO(r.result.err);
    REQUIRE(r.result.status == 0);
    // The pause came at the end of the layer it was asked in, as the
    // reading has it: with the marker, the end of an even layer by Z.
    const int asked = static_cast<int>(number_after(r.result.err, "pause: finishing layer "));
    REQUIRE(asked >= 1);
    auto last = static_cast<std::uint64_t>(number_after(r.result.err, "pause block sent after input line "));
    Checked c = gctest::check_one_pause(r.log, input, last);
    REQUIRE(c.prefix < input.size());
    const auto& layer_of = marked ? ply_layer : z_layer;
    CHECK(layer_of.at(input[c.prefix - 1].source_line) == asked);
    CHECK(layer_of.at(input[c.prefix].source_line) == asked + 1);
    CHECK(z_layer.at(input[c.prefix - 1].source_line) == (marked ? 2 * asked : asked));
    // The progress counted the layers beforehand (a regular file): paused
    // before the next of them, done at the last.
    const std::string n = std::to_string(marked ? ply_layers : z_layers);
    CHECK(r.result.out.find("\"state\": \"paused\", \"layer\": " + std::to_string(asked + 1) +
                            ", \"layers\": " + n + ",") != std::string::npos);
    CHECK(r.result.out.find("\"state\": \"done\", \"layer\": " + n + ", \"layers\": " + n + ",") != std::string::npos);
  }
}

TEST_CASE("gc-send --e-mode: a file that never says M82/M83 is read as told, and the pause's return follows",
          "[gc-send][reading]") {
  // Relative E amounts (the fixture's), its M83 lines left out.
  std::string text = fixture_layers(3, [](const std::string& line, int) { return line.rfind("M83", 0) != 0; });
  std::string file = gctest::temp_dir() + "/no_e_mode.gcode";
  gctest::write_file(file, text);
  auto input = gctest::commands_of(text);

  for (const char* mode : {"relative", "absolute", "auto"}) {
    INFO("--e-mode " << mode);
    PauseRun r = send_with_control(file, kVirtualSpec, std::string("--no-pace --e-mode ") + mode, kPauseInALayer);
    INFO(r.result.err);
    REQUIRE(r.result.status == 0);
    const bool guessed = std::string(mode) == "auto";
    CHECK((r.result.err.find("never sets the E mode (M82/M83); reading its E values as relative") !=
           std::string::npos) == guessed);
    const bool relative = std::string(mode) != "absolute";
    auto last = static_cast<std::uint64_t>(number_after(r.result.err, "pause block sent after input line "));
    Checked c = gctest::check_one_pause(r.log, input, last);
    // The blocks' E words: read relatively, as the file means them, they
    // retract and push back the same amount only when gc-send read the file
    // so; read as absolute, the return re-states the coordinate with G92 E.
    double pushed = 0, retracted = 0;
    int g92 = 0;
    for (std::size_t i = c.prefix; i < c.prefix + c.block; ++i) {
      gcode::Line line = gcode::Line::parse(r.log[i].command);
      if (line.is_g(92) && line.has('E')) ++g92;
      const gcode::Word* e = line.find('E');
      if (!line.is_move() || e == nullptr) continue;
      (e->value() < 0 ? retracted : pushed) += e->value();
    }
    CHECK(g92 == (relative ? 0 : 1));
    CHECK(retracted < -1);
    if (relative) {
      CHECK(pushed + retracted == Approx(0).margin(1e-9));
    } else {
      CHECK(pushed + retracted < -1);  // absolute coordinates, not amounts
    }
  }
}
