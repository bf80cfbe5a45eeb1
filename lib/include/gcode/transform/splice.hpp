#pragma once
// Splicing: joining blocks of G-code onto a stream at layer boundaries so
// that the printer cannot tell (background.md §1: continue with a re-sliced
// file, swap, skip and repeat layers). gc-swap-layer, gc-relayer and
// gc-send's live swap rest on it.
//
//   SpliceBlock   what to print: bytes [begin, end) of a file (one or more
//                 layers, or everything from a layer on, end code included),
//                 how the machine stands at `begin`, a Z shift and an
//                 extrusion factor. From a LayerIndex (layer_index_block) or
//                 from a layer of the main stream itself (--repeat).
//   BlockStream   prints one block: the seam (seam.hpp) from the printed
//                 side, then the block's lines with their Z shifted (exact
//                 decimals, the input's precision), E carried (G92 E, or
//                 rewritten into the printed side's E mode when the block's
//                 file uses the other one) and extrusion scaled. Pull style:
//                 each pump() writes the seam or one read's worth of lines to
//                 a SpliceSink, so memory stays flat whatever the sizes and a
//                 caller (gc-send) can pace it; run() pumps to the end.
//   SpliceStage   a pipeline stage over the main stream (push style). At each
//                 layer event a SplicePlan says what happens: keep or leave
//                 out the layer, shift Z from here on, scale its extrusion,
//                 print blocks first, or leave the main stream for good.
//                 Kept lines go on byte for byte (or with their Z and E
//                 rewritten); back into the main stream after a block or a
//                 gap comes another seam.
//
// Inside a block the lines run through a pipeline of their own (state and
// layers as in any file: layer events of the block are passed on), started
// from the indexed state by a few lines that are never written.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/diagnostics.hpp"
#include "gcode/core/layer_marker.hpp"
#include "gcode/core/line_builder.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/core/print_area.hpp"
#include "gcode/pipeline/stage.hpp"
#include "gcode/transform/layer_index.hpp"
#include "gcode/transform/pause_sequence.hpp"
#include "gcode/transform/seam.hpp"

namespace gcode {

struct SpliceBlock {
  int fd = -1;                       // read with pread; not owned
  std::string name;                  // for messages
  const LayerMarkers* markers = nullptr;
  std::uint64_t begin = 0;           // the first byte (a layer's start)
  std::uint64_t end = 0;             // one past the last byte
  bool through_end = false;          // the block ends with the file's end code (its event is passed on)
  std::uint64_t first_line = 1;      // the file's line number at `begin` (messages)
  LayerInfo first_layer;             // the layer at `begin`
  StreamPoint start;                 // how the file stands at `begin` (layer_z: first_layer.z)
  Fixed z_shift;                     // added to every absolute Z of the block
  double extrusion_scale = 1;        // factor for its extruding moves
  std::string note;                  // the seam's comment
  // The printed side stands exactly where this block starts (the block
  // printed last ended at `begin` of the same file, with the same shift):
  // no seam, the lines go on. Set by SpliceStage.
  bool continues = false;
};

// What differs between the printer a file was sliced for and the input's
// (the bed), as a warning text; empty when nothing is known to differ.
std::string printer_difference(const PrintArea& input, const PrintArea& other, const std::string& other_name);

// Whether another slicing of the part lies where the input prints: the
// centres of the two XY extents (what was printed, what the other file
// prints below the join) more than 2 mm apart means another printer or
// placement. Returns the error text, empty when they agree or either extent
// is empty.
std::string placement_difference(const Box2& printed, const Box2& theirs, const std::string& their_name);

// Layers first..last of an indexed file (through_end: first to the end of
// the file, end code included). The index must have reached them.
SpliceBlock layer_index_block(const LayerIndex& index, int first, int last, bool through_end = false);

// Where a block's output goes.
class SpliceSink {
 public:
  virtual ~SpliceSink() = default;
  virtual void line(std::string_view text) = 0;
  virtual void layer(const LayerInfo& info, const MachineState& before) = 0;
  virtual void end_code(const EndCodeInfo& info, const MachineState& before) = 0;
};

// Rewrites a stream's lines for a splice: Z shifted, E in the output's mode
// and coordinate, extrusion scaled. Lines that need none of it stay as they
// are (apply returns false).
class SpliceRewrite {
 public:
  // `relative_e`, `e`: the output's E mode and coordinate where the lines start.
  void reset(Fixed z_shift, double extrusion_scale, bool relative_e, Fixed e);
  // `precision`: the decimals to write at least (the output's).
  bool apply(const TrackedLine& t, const Precision& precision, std::string_view& text);
  bool identity() const { return identity_; }
  bool relative_e() const { return relative_e_; }
  Fixed e() const { return e_; }
  Fixed z_shift() const { return shift_; }
  double scale() const { return scale_; }

 private:
  Fixed scaled(Fixed amount, int decimals);
  Fixed shift_;
  double scale_ = 1;
  bool identity_ = true;
  bool relative_e_ = false;
  Fixed e_;
  Fixed source_pushed_;  // extruded by the source since reset (scaled moves)
  Fixed output_pushed_;  // written for them, rounded, the rounding carried
  std::string text_;
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
  RetractionTracker main_retraction_;
  CarriedSettings main_settings_;
  bool main_e_mode_set_ = false;
  std::uint64_t main_bytes_ = 0;  // the input read so far
  RetractionTracker main_retraction_lead_;  // the printed side during a lead-in
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
