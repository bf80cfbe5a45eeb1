#include "gcode/transform/splice_stage.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace gcode {

struct SpliceStage::Sink : SpliceSink {
  Sink(SpliceStage& stage, Emitter& out) : stage(stage), out(out) {}
  void line(std::string_view text) override { out.insert(text); }
  void layer(const LayerInfo& info, const MachineState& before) override {
    LayerInfo i = info;
    i.index = ++stage.layers_out_;
    out.layer(i, before);
  }
  void end_code(const EndCodeInfo& info, const MachineState& before) override { out.end_code(info, before); }
  SpliceStage& stage;
  Emitter& out;
};

SpliceStage::SpliceStage(SplicePlan& plan, const Precision& precision, SeamOptions options, Diagnostics* diag)
    : plan_(plan), precision_(precision), options_(options), diag_(diag) {
  if (!plan_.keeps_start_code()) {
    // Nothing is printed before the plan's lead-in: a machine just switched on.
    following_ = false;
    dropping_ = true;
  }
}

SpliceStage::~SpliceStage() = default;

double SpliceStage::top_z() const { return printed_.top_z; }

void SpliceStage::observe_main(const TrackedLine& t) {
  main_.follow(t.line, t.move, t.before.tool);
  if (t.origin == LineOrigin::Input) main_bytes_ = t.raw.offset + t.raw.size();
}

StreamPoint SpliceStage::main_point(const MachineState& before) const {
  StreamPoint p = main_;
  p.state = before;
  return p;
}

void SpliceStage::leave_main(const MachineState& before) {
  if (!following_) return;
  following_ = false;
  printed_.state = before;
  if (!shift_.is_zero()) printed_.state.set(kZ, before.at(kZ) + shift_);
  if (!rewrite_.identity()) {
    printed_.state.relative_e = rewrite_.relative_e();
    printed_.state.set(kE, rewrite_.e());
  }
  printed_.retracted = main_.retracted;
  printed_.settings = main_.settings;
  printed_.e_mode_set = main_.e_mode_set;
}

void SpliceStage::print_blocks(std::vector<SpliceBlock>& blocks, Emitter& out) {
  Sink sink(*this, out);
  for (SpliceBlock& b : blocks) {
    b.continues = last_fd_ == b.fd && last_end_ == b.begin && last_shift_ == b.z_shift && !last_scaled_ &&
                  b.extrusion_scale == 1;
    // A file in the other E mode is said once, not at every block of it.
    bool told = std::find(told_.begin(), told_.end(), b.name) != told_.end();
    BlockStream stream(b, printed_, options_, precision_, told ? nullptr : diag_);
    stream.set_copy_to_end(!downstream_reads_);
    stream.run(sink);
    if (stream.converted_e() && !told) told_.push_back(b.name);
    ++blocks_;
    if (!b.continues) ++seams_;
    last_fd_ = b.fd;
    last_end_ = b.end;
    last_shift_ = b.z_shift;
    last_scaled_ = b.extrusion_scale != 1;
  }
}

void SpliceStage::lead_in(const std::vector<std::string>& lines, Emitter& out) {
  for (const std::string& text : lines) {
    out.insert(text);
    Line line = Line::parse(text);
    const int tool = printed_.state.tool;
    printed_.follow(line, printed_.state.apply(line), tool);
  }
}

void SpliceStage::rejoin(StreamPoint target, const std::string& note, Emitter& out) {
  last_fd_ = -1;
  Seam seam;
  try {
    seam = build_seam(printed_, target, options_, precision_, false);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(fmt::format("cannot go back to the input here: {}", e.what()));
  }
  if (!note.empty()) out.insert("; " + note);
  for (const std::string& l : seam.lines) out.insert(l);
  following_ = true;
  ++seams_;
}

SpliceContext SpliceStage::context(const MachineState& before) {
  main_here_ = main_point(before);
  SpliceContext c;
  c.shift = shift_;
  c.top_z = printed_.top_z;
  c.extent = printed_.extent;
  c.previous = has_previous_ ? &previous_ : nullptr;
  c.main = &main_here_;
  c.layers_out = layers_out_;
  return c;
}

void SpliceStage::close_current(std::uint64_t end) {
  if (!has_current_) return;
  current_.end = end;
  previous_ = current_;
  has_previous_ = true;
  has_current_ = false;
}

// Blocks first, then what happens to the main stream itself. Returns whether
// the main stream goes on here.
bool SpliceStage::begin(LayerAction& action, const MachineState& before, Emitter& out) {
  if (!action.blocks.empty()) {
    leave_main(before);
    print_blocks(action.blocks, out);
  }
  if (action.leave) {
    leave_main(before);
    left_ = dropping_ = true;
    return false;
  }
  if (!action.keep) {
    leave_main(before);
    dropping_ = true;
    shift_ = action.shift;
    return false;
  }
  if (following_ && (action.shift != shift_ || !action.lead_in.empty())) leave_main(before);
  if (!action.lead_in.empty()) lead_in(action.lead_in, out);
  printed_.top_z = std::max(printed_.top_z, action.printed_top);
  shift_ = action.shift;
  dropping_ = false;
  return true;
}

// After the main stream's own event: the seam back into it, or the E
// coordinate when the last layer's extrusion was scaled.
void SpliceStage::resume(const LayerAction& action, const MachineState& before, double layer_z, Emitter& out) {
  if (!following_) {
    StreamPoint target = main_point(before);
    if (!shift_.is_zero() && target.state.known[kZ]) target.state.set(kZ, before.at(kZ) + shift_);
    target.layer_z = layer_z;
    rejoin(std::move(target), action.note, out);
  } else if (!rewrite_.identity() && rewrite_.e() != before.at(kE)) {
    out.insert(builder_.start("G92").fixed('E', before.at(kE)).view());
  }
  rewrite_.reset(shift_, action.extrusion_scale, before.relative_e, before.at(kE));
}

void SpliceStage::layer(const LayerInfo& info, const MachineState& before, Emitter& out) {
  close_current(info.offset);
  current_.info = info;
  current_.start = main_point(before);
  current_.start.layer_z = info.z;
  has_current_ = true;
  if (left_) return;
  LayerAction action = plan_.at_layer(info, context(before));
  if (!begin(action, before, out)) {
    if (!left_) ++left_out_;
    return;
  }
  ++kept_;
  LayerInfo shifted = info;
  shifted.z += shift_.to_double();
  shifted.index = ++layers_out_;
  out.layer(shifted, before);
  resume(action, before, shifted.z, out);
}

void SpliceStage::end_code(const EndCodeInfo& info, const MachineState& before, Emitter& out) {
  // The last layer ends where the end code starts, or with the input.
  close_current(info.first_line != 0 ? info.offset : main_bytes_);
  if (left_) return;
  LayerAction action = plan_.at_end_code(context(before));
  if (!begin(action, before, out)) return;
  out.end_code(info, before);
  resume(action, before, (before.at(kZ) + shift_).to_double(), out);
}

void SpliceStage::line(const TrackedLine& t, Emitter& out) {
  observe_main(t);
  if (dropping_) return;
  std::string_view text;
  if (!rewrite_.identity() && rewrite_.apply(t, precision_, text)) {
    out.replace(t, text);
  } else {
    out.pass(t);
  }
  printed_.printed(t.move, t.region, shift_.to_double());
}

}  // namespace gcode
