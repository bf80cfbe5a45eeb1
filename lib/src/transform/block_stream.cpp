#include "gcode/transform/block_stream.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <stdexcept>
#include <system_error>

#include "gcode/pipeline/pipeline.hpp"
#include "gcode/transform/splice_rewrite.hpp"

namespace gcode {

namespace {

constexpr std::size_t kBlockRead = 1 << 16;

// The output's state for a state of the source: Z shifted, E as written.
MachineState shifted_state(const MachineState& source, Fixed shift, bool relative_e, Fixed e) {
  MachineState s = source;
  if (!shift.is_zero()) s.set(kZ, s.at(kZ) + shift);
  s.relative_e = relative_e;
  s.set(kE, e);
  return s;
}

// The lines that put a fresh pipeline into `s` without moving anything:
// they are fed first and never written.
std::string prelude_for(const MachineState& s, int& lines) {
  LineBuilder b;
  std::string text = "G90\n";
  lines = 1;
  b.start("G92");
  bool any = false;
  for (int a = 0; a < 4; ++a) {
    if (!s.known[static_cast<std::size_t>(a)] && a != kE) continue;
    b.fixed("XYZE"[a], s.at(a));
    any = true;
  }
  if (any) {
    text.append(b.view()).push_back('\n');
    ++lines;
  }
  if (s.feedrate > 0) {
    b.start("G1").fixed('F', Fixed::from_double(s.feedrate));
    text.append(b.view()).push_back('\n');
    ++lines;
  }
  if (s.tool != 0) {
    text += fmt::format("T{}\n", s.tool);
    ++lines;
  }
  if (s.relative_xyz) {
    text += "G91\n";
    ++lines;
  }
  if (s.relative_e != s.relative_xyz) {
    text += s.relative_e ? "M83\n" : "M82\n";
    ++lines;
  }
  if (s.firmware_retracted) {
    text += "G10\n";
    ++lines;
  }
  return text;
}

}  // namespace

// The block pipeline's one stage: rewrites the block's lines and hands them
// to the sink, keeping the printed side up to date.
class BlockStream::Bridge : public Stage {
 public:
  Bridge(BlockStream& owner, int prelude_lines, double retracted)
      : owner_(owner), pipeline_(*owner.block_.markers), prelude_(static_cast<std::uint64_t>(prelude_lines)) {
    pipeline_.add(*this);
    // Past the seam the printer is retracted as the file is where the block starts.
    owner_.printed_.retracted = retracted;
  }
  Pipeline& pipeline() { return pipeline_; }
  void set_sink(SpliceSink* sink) { sink_ = sink; }
  SpliceRewrite& rewrite() { return rewrite_; }

  void line(const TrackedLine& t, Emitter&) override {
    if (t.raw.number <= prelude_) return;
    owner_.printed_.observe(t, rewrite_.z_shift().to_double());
    std::string_view text = t.raw.text;
    rewrite_.apply(t, owner_.precision_, text);
    sink_->line(text);
  }

  void layer(const LayerInfo& info, const MachineState& before, Emitter&) override {
    // The first layer's event went out before the seam.
    if (!first_seen_) {
      first_seen_ = true;
      return;
    }
    LayerInfo shifted = info;
    shifted.z += rewrite_.z_shift().to_double();
    shifted.first_line = info.first_line > prelude_ ? owner_.block_.first_line + info.first_line - prelude_ - 1 : 0;
    sink_->layer(shifted, output_state(before));
  }

  void end_code(const EndCodeInfo& info, const MachineState& before, Emitter&) override {
    if (!owner_.block_.through_end) return;
    EndCodeInfo i = info;
    if (i.first_line > prelude_) i.first_line = owner_.block_.first_line + i.first_line - prelude_ - 1;
    sink_->end_code(i, output_state(before));
  }

  MachineState output_state(const MachineState& source) const {
    return shifted_state(source, rewrite_.z_shift(), rewrite_.relative_e(), rewrite_.e());
  }

 private:
  BlockStream& owner_;
  Pipeline pipeline_;
  std::uint64_t prelude_;  // the first lines fed are the prelude
  SpliceSink* sink_ = nullptr;
  SpliceRewrite rewrite_;
  bool first_seen_ = false;
};

BlockStream::BlockStream(const SpliceBlock& block, StreamPoint& printed, const SeamOptions& options,
                         const Precision& precision, Diagnostics* diag)
    : block_(block), printed_(printed), options_(options), precision_(precision), diag_(diag) {
  if (block_.markers == nullptr) throw std::logic_error("SpliceBlock without layer markers");
  next_ = block_.begin;
}

BlockStream::~BlockStream() = default;

bool BlockStream::pump(SpliceSink& sink) {
  if (done_) return false;
  if (!started_) {
    started_ = true;
    // The block as the file has it, moved by the shift.
    StreamPoint target = block_.start;
    if (!block_.z_shift.is_zero() && target.state.known[kZ])
      target.state.set(kZ, target.state.at(kZ) + block_.z_shift);
    target.layer_z = block_.first_layer.z + block_.z_shift.to_double();
    LayerInfo first = block_.first_layer;
    first.z = target.layer_z;
    sink.layer(first, printed_.state);
    if (!block_.note.empty() && !block_.continues) sink.line("; " + block_.note);
    if (block_.continues) {
      // The printer is where the block starts: its E mode and coordinate go on.
      seam_.relative_e = printed_.state.relative_e;
      seam_.e_mode_differs = printed_.state.relative_e != target.state.relative_e;
      target.state.set(kE, printed_.state.at(kE));
    } else {
      try {
        seam_ = build_seam(printed_, target, options_, precision_, true);
      } catch (const std::invalid_argument& e) {
        throw std::runtime_error(fmt::format("cannot join {} here: {}", block_.name, e.what()));
      }
      for (const std::string& l : seam_.lines) sink.line(l);
    }
    // The printed side now stands as the block expects, in the E mode the
    // seam left (the block's, or the printed side's when it is rewritten).
    printed_.settings.adopt(target.settings);
    if (seam_.e_mode_differs && diag_ != nullptr && !block_.continues)
      diag_->warn(fmt::format("{} uses {} E and the output {}: its E values are written as {}", block_.name,
                              target.state.relative_e ? "relative" : "absolute",
                              seam_.relative_e ? "relative" : "absolute",
                              seam_.relative_e ? "relative amounts" : "absolute coordinates"));
    copying_ = copy_to_end_ && block_.through_end && block_.z_shift.is_zero() && block_.extrusion_scale == 1 &&
               !seam_.e_mode_differs;
    if (copying_) {
      copy_lines_ = std::make_unique<LineSplitter>(kBlockRead);
      return true;
    }
    int prelude_lines = 0;
    std::string prelude = prelude_for(block_.start.state, prelude_lines);
    bridge_ = std::make_unique<Bridge>(*this, prelude_lines, block_.start.retracted);
    bridge_->rewrite().reset(block_.z_shift, block_.extrusion_scale, seam_.relative_e, target.state.at(kE));
    bridge_->set_sink(&sink);
    bridge_->pipeline().feed(prelude);
    return true;
  }
  if (copying_) return copy(sink);
  bridge_->set_sink(&sink);
  if (next_ < block_.end) {
    buffer_.resize(kBlockRead);
    std::size_t want = static_cast<std::size_t>(std::min<std::uint64_t>(buffer_.size(), block_.end - next_));
    ssize_t n;
    do {
      n = ::pread(block_.fd, buffer_.data(), want, static_cast<off_t>(next_));
    } while (n < 0 && errno == EINTR);
    if (n < 0) throw std::system_error(errno, std::generic_category(), "cannot read " + block_.name);
    if (n > 0) {
      next_ += static_cast<std::uint64_t>(n);
      bridge_->pipeline().feed(std::string_view(buffer_.data(), static_cast<std::size_t>(n)));
      return true;
    }
  }
  bridge_->pipeline().finish();
  finish();
  return false;
}

bool BlockStream::copy(SpliceSink& sink) {
  LineSplitter& lines = *copy_lines_;
  char* room = lines.room();
  ssize_t n;
  do {
    n = ::pread(block_.fd, room, lines.room_size(), static_cast<off_t>(next_));
  } while (n < 0 && errno == EINTR);
  if (n < 0) throw std::system_error(errno, std::generic_category(), "cannot read " + block_.name);
  if (n == 0) lines.end_of_input();
  next_ += static_cast<std::uint64_t>(n);
  lines.commit(static_cast<std::size_t>(n));
  RawLine raw;
  while (lines.next(raw)) sink.line(raw.text);
  if (n == 0) done_ = true;
  return n != 0;
}

void BlockStream::finish() {
  done_ = true;
  const MachineState& source = bridge_->pipeline().tracker().state();
  printed_.state = bridge_->output_state(source);
}

}  // namespace gcode
