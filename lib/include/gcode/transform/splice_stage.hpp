#pragma once
// A pipeline stage over the main stream of a splice (push style). At each
// layer event a SplicePlan says what happens: keep or leave out the layer,
// shift Z from here on, scale its extrusion, print blocks first
// (block_stream.hpp), or leave the main stream for good. Kept lines go on
// byte for byte (or with their Z and E rewritten, splice_rewrite.hpp); back
// into the main stream after a block or a gap comes another seam.
#include <cstdint>
#include <string>
#include <vector>

#include "gcode/core/diagnostics.hpp"
#include "gcode/core/fixed.hpp"
#include "gcode/core/geometry.hpp"
#include "gcode/core/line_builder.hpp"
#include "gcode/pipeline/stage.hpp"
#include "gcode/transform/block_stream.hpp"
#include "gcode/transform/seam.hpp"
#include "gcode/transform/splice_block.hpp"
#include "gcode/transform/splice_rewrite.hpp"
#include "gcode/transform/stream_tracker.hpp"

namespace gcode {


// A main-stream layer as the stage saw it pass (to print it again).
struct PassedLayer {
  LayerInfo info;
  std::uint64_t end = 0;
  StreamPoint start;
};

// What the plan knows when it decides.
struct SpliceContext {
  Fixed shift;                       // the main stream's Z shift so far
  double top_z = 0;                  // the highest Z printed so far
  Box2 extent;                       // XY extent printed so far (layers only)
  const PassedLayer* previous = nullptr;  // the main layer before this point, complete
  const StreamPoint* main = nullptr;      // the main stream here: state, retraction, settings
  int layers_out = 0;                // layers written so far
};

// What happens at one main-stream layer (or its end code).
struct LayerAction {
  std::vector<SpliceBlock> blocks;   // printed first (after the previous layer)
  bool keep = true;                  // print this main layer (the end code: keep it)
  Fixed shift;                       // Z shift of this layer and everything after it
  double extrusion_scale = 1;        // factor for this layer's extruding moves
  bool leave = false;                // drop the main stream from here to its end, end code included
  std::vector<std::string> lead_in;  // lines before the seam back into this layer (resume)
  double printed_top = 0;            // a height printed that the stream does not show (resume)
  std::string note;                  // comment of the seam back into this layer
};

class SplicePlan {
 public:
  virtual ~SplicePlan() = default;
  virtual LayerAction at_layer(const LayerInfo& info, const SpliceContext& context) = 0;
  virtual LayerAction at_end_code(const SpliceContext& context) = 0;
  // False: the main stream's start code is left out (resume).
  virtual bool keeps_start_code() const { return true; }
};

class SpliceStage : public Stage {
 public:
  // `precision`: the main pipeline's (Pipeline::precision). `diag` may be null.
  SpliceStage(SplicePlan& plan, const Precision& precision, SeamOptions options, Diagnostics* diag = nullptr);
  ~SpliceStage() override;

  void layer(const LayerInfo& info, const MachineState& before, Emitter& out) override;
  void end_code(const EndCodeInfo& info, const MachineState& before, Emitter& out) override;
  void line(const TrackedLine& t, Emitter& out) override;

  int layers_kept() const { return kept_; }
  int layers_left_out() const { return left_out_; }
  int blocks() const { return blocks_; }
  int seams() const { return seams_; }
  int layers_out() const { return layers_out_; }
  // The main stream was left for good: nothing more of it is needed.
  bool left() const { return left_; }
  // The printed side: where the output stands once the main stream was left
  // (or after the last block). A caller that paces a block itself (gc-send)
  // lets its plan leave without blocks and hands this to a BlockStream.
  StreamPoint& printed() { return printed_; }
  // The highest Z printed, for checks after the run.
  double top_z() const;
  // False when nothing after this stage reads layer events or states (a
  // filter tool's writer): a file joined for good is then copied to its end
  // without parsing (BlockStream::set_copy_to_end).
  void set_downstream_reads(bool on) { downstream_reads_ = on; }

 private:
  struct Sink;
  void observe_main(const TrackedLine& t);
  StreamPoint main_point(const MachineState& before) const;
  void close_current(std::uint64_t end);
  void leave_main(const MachineState& before);
  void print_blocks(std::vector<SpliceBlock>& blocks, Emitter& out);
  void lead_in(const std::vector<std::string>& lines, Emitter& out);
  void rejoin(StreamPoint target, const std::string& note, Emitter& out);
  bool begin(LayerAction& action, const MachineState& before, Emitter& out);
  void resume(const LayerAction& action, const MachineState& before, double layer_z, Emitter& out);
  SpliceContext context(const MachineState& before);

  SplicePlan& plan_;
  const Precision& precision_;
  SeamOptions options_;
  Diagnostics* diag_;
  // The main stream.
  StreamPoint main_;  // retraction, settings and E mode (its state is the pipeline's)
  std::uint64_t main_bytes_ = 0;  // the input read so far
  PassedLayer current_, previous_;
  bool has_current_ = false, has_previous_ = false;
  StreamPoint main_here_;  // scratch for SpliceContext::main
  // The output.
  bool following_ = true;   // the output is the main stream (with shift_): `printed_` is derived from it
  bool dropping_ = false;   // main lines are left out
  bool left_ = false;       // the main stream was left for good
  StreamPoint printed_;     // the printed side while not following
  Box2 extent_;             // while following
  Fixed shift_;
  SpliceRewrite rewrite_;
  int kept_ = 0, left_out_ = 0, blocks_ = 0, seams_ = 0, layers_out_ = 0;
  // The block printed last, to go straight on with the next one when it
  // starts where that one ended.
  int last_fd_ = -1;
  std::uint64_t last_end_ = 0;
  Fixed last_shift_;
  bool last_scaled_ = false;
  bool downstream_reads_ = true;
  std::vector<std::string> told_;  // files whose E mode differs, warned about
  LineBuilder builder_;
};

}  // namespace gcode
