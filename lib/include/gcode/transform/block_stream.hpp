#pragma once
// Prints one splice block: the seam (seam.hpp) from the printed side, then
// the block's lines with their Z shifted, E carried (G92 E, or rewritten into
// the printed side's E mode when the block's file uses the other one) and
// extrusion scaled (splice_rewrite.hpp). Pull style: each pump() writes the
// seam or one read's worth of lines to a SpliceSink, so memory stays flat
// whatever the sizes and a caller (gc-send) can pace it; run() pumps to the
// end.
//
// Inside a block the lines run through a pipeline of their own (state and
// layers as in any file: layer events of the block are passed on), started
// from the indexed state by a few lines that are never written.
#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include "gcode/core/diagnostics.hpp"
#include "gcode/core/layer_tracker.hpp"
#include "gcode/core/line_builder.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/pipeline/stage.hpp"
#include "gcode/transform/seam.hpp"
#include "gcode/transform/splice_block.hpp"
#include "gcode/transform/stream_tracker.hpp"

namespace gcode {

// Where a block's output goes.
class SpliceSink {
 public:
  virtual ~SpliceSink() = default;
  virtual void line(std::string_view text) = 0;
  virtual void layer(const LayerInfo& info, const MachineState& before) = 0;
  virtual void end_code(const EndCodeInfo& info, const MachineState& before) = 0;
};

class BlockStream {
 public:
  // `printed` is the printed side: read for the seam, updated as the block
  // is written (position, E, retraction, settings, top Z). `precision`: the
  // output's decimals (the main input's). `diag` may be null.
  BlockStream(const SpliceBlock& block, StreamPoint& printed, const SeamOptions& options, const Precision& precision,
              Diagnostics* diag = nullptr);
  ~BlockStream();
  BlockStream(const BlockStream&) = delete;
  BlockStream& operator=(const BlockStream&) = delete;

  // Writes the next piece to `sink`: first the block's layer event and the
  // seam, then one read of the block's lines. False once the block is done.
  bool pump(SpliceSink& sink);
  void run(SpliceSink& sink) {
    while (pump(sink)) {
    }
  }
  const Seam& seam() const { return seam_; }
  // The block's E was rewritten into the printed side's mode.
  bool converted_e() const { return seam_.e_mode_differs; }
  // For a block that runs to the end of its file and needs no rewriting (no
  // shift, no scale, the same E mode) when nothing after it reads layers or
  // states (a filter's writer): its lines are copied as they are, without
  // parsing and without layer events; `printed` is not updated past the
  // seam. Call before the first pump().
  void set_copy_to_end(bool on) { copy_to_end_ = on; }

 private:
  class Bridge;
  void finish();
  bool copy(SpliceSink& sink);

  SpliceBlock block_;
  StreamPoint& printed_;
  SeamOptions options_;
  const Precision& precision_;
  Diagnostics* diag_;
  Seam seam_;
  std::unique_ptr<Bridge> bridge_;
  std::vector<char> buffer_;
  std::uint64_t next_ = 0;  // the next byte to read
  bool started_ = false;
  bool done_ = false;
  bool copy_to_end_ = false;
  bool copying_ = false;  // copy_to_end_ and the block allows it
  std::unique_ptr<LineSplitter> copy_lines_;
};

}  // namespace gcode
