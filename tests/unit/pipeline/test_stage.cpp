// A stage and its Emitter (pipeline/stage.hpp): pass, drop, replace and
// insert in the order they are called; each later stage sees the true state
// of the stream it receives (after the stages before it changed it) and the
// link falls back in step with the input once the states agree; a stage
// switched off mid-stream is skipped; lines added around layer events and at
// the end take the context they belong to.
#include <catch2/catch.hpp>

#include <functional>
#include <string>
#include <vector>

#include "gcode/pipeline/pipeline.hpp"
#include "gcode/pipeline/stage.hpp"
#include "fn_stage.hpp"
#include "test_support.hpp"

using gcode::Emitter;
using gcode::LineOrigin;
using gcode::Region;
using gcode::Stage;
using gcode::TrackedLine;
using gctest::FnStage;

namespace {

// What a stage further down saw of each line.
struct Seen {
  std::string text;
  LineOrigin origin;
  double x_before, x_after, z_after;
  Region region;
  int layer;
  std::uint64_t number;
};

class StageRecorder : public Stage {
 public:
  void line(const TrackedLine& t, Emitter& out) override {
    seen.push_back({std::string(t.raw.text), t.origin, t.before.position[gcode::kX], t.state.position[gcode::kX],
                    t.state.position[gcode::kZ], t.region, t.layer, t.raw.number});
    out.pass(t);
  }
  void layer(const gcode::LayerInfo& info, const gcode::MachineState& before, Emitter& out) override {
    layers.push_back(info.index);
    out.layer(info, before);
  }
  std::vector<Seen> seen;
  std::vector<int> layers;
};

bool is(const TrackedLine& t, std::string_view text) { return t.raw.text == text; }

}  // namespace

TEST_CASE("stage: pass, drop, replace and insert, in the order called", "[stage]") {
  FnStage edit([](const TrackedLine& t, Emitter& out) {
    if (is(t, "G1 X1")) {
      out.insert("; before X1");
      out.pass(t);
      out.insert("; after X1");
    } else if (is(t, "G1 X2")) {
      // dropped
    } else if (is(t, "G1 X3")) {
      out.replace(t, "G1 X33");
    } else if (is(t, "G1 X4")) {
      out.insert_lines("M117 a\r\n\nM117 b\nM117 c");
    } else {
      out.pass(t);
    }
  });
  std::string out = gctest::run_stages("G1 X1\nG1 X2\nG1 X3 ; comment\nG1 X3\nG1 X4\nG1 X5\n", {&edit}, false);
  CHECK(out == "; before X1\nG1 X1\n; after X1\nG1 X3 ; comment\nG1 X33\nM117 a\nM117 b\nM117 c\nG1 X5\n");
}

TEST_CASE("stage: a later stage sees the stream as changed, with its states", "[stage]") {
  FnStage edit([](const TrackedLine& t, Emitter& out) {
    if (is(t, "G1 X10")) {
      out.replace(t, "G1 X20");
    } else if (is(t, "G1 Y5")) {
      out.insert("G1 Z7");
      out.pass(t);
    } else {
      out.pass(t);
    }
  });
  StageRecorder rec;
  gctest::run_stages("G1 X10\nG1 Y5\nG1 X30\nG1 Y6\n", {&edit, &rec}, false);
  REQUIRE(rec.seen.size() == 5);
  CHECK(rec.seen[0].text == "G1 X20");
  CHECK(rec.seen[0].origin == LineOrigin::Changed);
  CHECK(rec.seen[0].number == 1);
  CHECK(rec.seen[0].x_after == 20);
  CHECK(rec.seen[1].text == "G1 Z7");
  CHECK(rec.seen[1].origin == LineOrigin::Inserted);
  CHECK(rec.seen[1].x_before == 20);  // the changed stream, not the input's X10
  CHECK(rec.seen[1].z_after == 7);
  CHECK(rec.seen[1].number == 2);     // the input line it came with
  CHECK(rec.seen[2].text == "G1 Y5");
  CHECK(rec.seen[2].origin == LineOrigin::Input);
  CHECK(rec.seen[2].x_after == 20);
  CHECK(rec.seen[2].z_after == 7);
  CHECK(rec.seen[3].x_before == 20);
  CHECK(rec.seen[3].x_after == 30);
  CHECK(rec.seen[3].z_after == 7);    // still its own stream: Z differs from the input's
  CHECK(rec.seen[4].x_after == 30);
}

TEST_CASE("stage: a later stage does not see the state of a dropped line", "[stage]") {
  FnStage drop([](const TrackedLine& t, Emitter& out) {
    if (!is(t, "G1 X10")) out.pass(t);
  });
  StageRecorder rec;
  std::string out = gctest::run_stages("G1 X1\nG1 X10\nG1 Y5\nG1 X30\nG1 Y6\n", {&drop, &rec}, false);
  CHECK(out == "G1 X1\nG1 Y5\nG1 X30\nG1 Y6\n");
  REQUIRE(rec.seen.size() == 4);
  CHECK(rec.seen[1].text == "G1 Y5");
  CHECK(rec.seen[1].x_before == 1);  // X10 never reached this stage
  CHECK(rec.seen[1].x_after == 1);
  CHECK(rec.seen[2].x_before == 1);
  CHECK(rec.seen[2].x_after == 30);
  CHECK(rec.seen[3].x_before == 30);  // back in step with the input
}

TEST_CASE("stage: the emitter's state is what an inserted line starts from", "[stage]") {
  std::vector<double> z_seen;
  FnStage probe([&](const TrackedLine& t, Emitter& out) {
    if (is(t, "G1 X2")) {
      z_seen.push_back(out.state().position[gcode::kZ]);  // before the line: the input's
      out.insert("G1 Z3");
      z_seen.push_back(out.state().position[gcode::kZ]);
      out.pass(t);
      z_seen.push_back(out.state().position[gcode::kZ]);
      return;
    }
    out.pass(t);
  });
  StageRecorder rec;  // reads states: inserted lines are applied
  gctest::run_stages("G1 Z1\nG1 X2\n", {&probe, &rec}, false);
  CHECK(z_seen == std::vector<double>{1, 3, 3});
}

TEST_CASE("stage: switched off mid-stream, a stage is skipped until switched on", "[stage]") {
  FnStage upper([](const TrackedLine& t, Emitter& out) { out.replace(t, std::string(t.raw.text) + " ; seen"); });
  FnStage control([&](const TrackedLine& t, Emitter& out) {
    if (is(t, "G1 X2")) upper.set_enabled(false);
    if (is(t, "G1 X4")) upper.set_enabled(true);
    out.pass(t);
  });
  StageRecorder rec;
  std::string out = gctest::run_stages("G1 X1\nG1 X2\nG1 X3\nG1 X4\n", {&control, &upper, &rec}, false);
  CHECK(out == "G1 X1 ; seen\nG1 X2\nG1 X3\nG1 X4 ; seen\n");
  REQUIRE(rec.seen.size() == 4);
  CHECK(rec.seen[1].origin == LineOrigin::Input);
  CHECK(rec.seen[3].origin == LineOrigin::Changed);
  CHECK(upper.enabled());
}

TEST_CASE("stage: lines added before a layer event end the previous layer", "[stage]") {
  class Marker : public Stage {
   public:
    void layer(const gcode::LayerInfo& info, const gcode::MachineState& before, Emitter& out) override {
      out.insert("; end of layer " + std::to_string(info.index - 1));
      out.layer(info, before);
      out.insert("; start of layer " + std::to_string(info.index));
    }
    void end_code(const gcode::EndCodeInfo& info, const gcode::MachineState& before, Emitter& out) override {
      out.end_code(info, before);
      out.insert("; end code");
    }
    void finish(Emitter& out) override { out.insert("; finished"); }
  } marker;
  StageRecorder rec;
  std::string text = ";LAYER:0\nG1 Z0.2\nG1 X1 E1\n;LAYER:1\nG1 Z0.4\nG1 X2 E2\nM84\n";
  std::string out = gctest::run_stages(text, {&marker, &rec});
  CHECK(out ==
        "; end of layer 0\n; start of layer 1\n;LAYER:0\nG1 Z0.2\nG1 X1 E1\n"
        "; end of layer 1\n; start of layer 2\n;LAYER:1\nG1 Z0.4\nG1 X2 E2\n"
        "; end code\nM84\n; finished\n");
  CHECK(rec.layers == std::vector<int>{1, 2});
  auto find = [&](std::string_view s) {
    for (const Seen& x : rec.seen)
      if (x.text == s) return x;
    FAIL("no line " << s);
    return rec.seen.front();
  };
  CHECK(find("; end of layer 0").region == Region::StartCode);
  CHECK(find("; start of layer 1").region == Region::Layer);
  CHECK(find("; start of layer 1").layer == 1);
  CHECK(find("; end of layer 1").layer == 1);
  CHECK(find("; start of layer 2").layer == 2);
  CHECK(find("; end code").region == Region::EndCode);
  CHECK(find("; finished").region == Region::EndCode);
  CHECK(find("; finished").z_after == 0.4);
}

TEST_CASE("stage: replace keeps the input line's ending, even a missing one", "[stage]") {
  FnStage edit([](const TrackedLine& t, Emitter& out) { out.replace(t, "G1 X9"); });
  CHECK(gctest::run_stages("G1 X1\r\nG1 X2", {&edit}, false) == "G1 X9\r\nG1 X9");
}
