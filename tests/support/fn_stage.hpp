#pragma once
// A pipeline stage made of functions, for tests of the pipeline's rules:
// line() calls `line`, finish() calls `at_end` (if given).
#include <functional>
#include <utility>

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

}  // namespace gctest
