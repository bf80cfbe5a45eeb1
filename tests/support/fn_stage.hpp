#pragma once
// Pipeline stages for tests of the pipeline's rules: FnStage, made of
// functions (line() calls `line`, finish() calls `at_end` if given), and
// SelectionStage, which keeps a LayerSelection told of layers and end code.
#include <functional>
#include <utility>

#include "gcode/pipeline/selection.hpp"
#include "gcode/pipeline/stage.hpp"

namespace gctest {

class FnStage : public gcode::Stage {
 public:
  using LineFn = std::function<void(const gcode::TrackedLine&, gcode::Emitter&)>;
  using EndFn = std::function<void(gcode::Emitter&)>;
  explicit FnStage(LineFn line, EndFn at_end = {}) : line_(std::move(line)), end_(std::move(at_end)) {}
  void line(const gcode::TrackedLine& t, gcode::Emitter& out) override { line_(t, out); }
  void finish(gcode::Emitter& out) override {
    if (end_) end_(out);
  }

 private:
  LineFn line_;
  EndFn end_;
};

// Derived stages ask sel.selects(t) in line().
class SelectionStage : public gcode::Stage {
 public:
  gcode::LayerSelection sel;
  void layer(const gcode::LayerInfo& info, const gcode::MachineState& before, gcode::Emitter& out) override {
    sel.enter_layer(info);
    out.layer(info, before);
  }
  void end_code(const gcode::EndCodeInfo& info, const gcode::MachineState& before, gcode::Emitter& out) override {
    sel.enter_end_code();
    out.end_code(info, before);
  }
};

}  // namespace gctest
