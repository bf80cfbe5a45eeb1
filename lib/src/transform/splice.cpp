#include "gcode/transform/splice.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <stdexcept>
#include <system_error>

#include "gcode/core/line_edit.hpp"
#include "gcode/core/number.hpp"
#include "gcode/pipeline/pipeline.hpp"

namespace gcode {

namespace {

constexpr std::size_t kBlockRead = 1 << 16;

int at_least(const Precision& p, char letter, int decimals) { return std::max(p.of(letter), decimals); }

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

// ---------------------------------------------------------------------------
// SpliceRewrite

void SpliceRewrite::reset(Fixed z_shift, double extrusion_scale, bool relative_e, Fixed e) {
  shift_ = z_shift;
  scale_ = extrusion_scale;
  relative_e_ = relative_e;
  e_ = e;
  source_pushed_ = Fixed();
  output_pushed_ = Fixed();
  identity_ = shift_.is_zero() && scale_ == 1;
}

Fixed SpliceRewrite::scaled(Fixed amount, int decimals) {
  // The running total is scaled and rounded, so rounding never adds up.
  source_pushed_ += amount;
  Fixed total = Fixed::from_double(source_pushed_.to_double() * scale_).rounded(decimals);
  Fixed piece = total - output_pushed_;
  output_pushed_ = total;
  return piece;
}

bool SpliceRewrite::apply(const TrackedLine& t, const Precision& precision, std::string_view& text) {
  const Line& l = t.line;
  if (l.kind != CommandKind::Standard) return false;
  if (l.letter == 'M') {
    if (l.number == 82 || l.number == 83) relative_e_ = t.state.relative_e;
    return false;
  }
  if (l.letter != 'G' || l.subcode >= 0) return false;
  const Word* z = nullptr;
  bool need_z = false, need_e = false;
  Fixed new_e;
  switch (l.number) {
    case 0: case 1: case 2: case 3: {
      if (t.move.ignored) return false;
      z = l.find('Z');
      need_z = !shift_.is_zero() && z != nullptr && z->has_value && !t.before.relative_xyz;
      const Word* e = l.find('E');
      if (e != nullptr && e->has_value) {
        Fixed delta = t.state.at(kE) - t.before.at(kE);
        Fixed out = delta;
        if (scale_ != 1 && t.move.extruding) out = scaled(delta, precision.of('E'));
        e_ += out;
        if (relative_e_) {
          new_e = out;
          need_e = !t.before.relative_e || out != delta;
        } else {
          new_e = e_;
          need_e = t.before.relative_e || e_ != t.state.at(kE);
        }
      }
      break;
    }
    case 92: {
      z = l.find('Z');
      need_z = !shift_.is_zero() && z != nullptr && z->has_value;
      const Word* e = l.find('E');
      if (e != nullptr && e->has_value) e_ = t.state.at(kE);
      break;
    }
    case 90: case 91:
      relative_e_ = t.state.relative_e;
      return false;
    default:
      return false;
  }
  if (!need_z && !need_e) return false;
  LineEdit edit(l);
  if (need_z) edit.set('Z', z->fixed() + shift_, at_least(precision, 'Z', z->decimals));
  if (need_e) edit.set('E', new_e, at_least(precision, 'E', l.find('E')->decimals));
  text_.assign(edit.text());
  text = text_;
  return true;
}

// ---------------------------------------------------------------------------
// BlockStream

std::string printer_difference(const PrintArea& input, const PrintArea& other, const std::string& other_name) {
  if (!input.has_bed || !other.has_bed) return {};
  auto same = [](double a, double b) { return std::fabs(a - b) < 0.5; };
  const Box2& a = input.bed;
  const Box2& b = other.bed;
  if (same(a.min_x, b.min_x) && same(a.min_y, b.min_y) && same(a.max_x, b.max_x) && same(a.max_y, b.max_y)) return {};
  char w[kMaxNumberChars], d[kMaxNumberChars], w2[kMaxNumberChars], d2[kMaxNumberChars];
  return fmt::format("{} was sliced for a {}x{} mm bed, the input for {}x{} mm: its moves are used as they are", other_name,
                     number_text(b.width(), 1, w), number_text(b.depth(), 1, d), number_text(a.width(), 1, w2),
                     number_text(a.depth(), 1, d2));
}

std::string placement_difference(const Box2& printed, const Box2& theirs, const std::string& their_name) {
  constexpr double kPlacement = 2.0;
  if (printed.empty() || theirs.empty()) return {};
  Point2 a = printed.centre(), b = theirs.centre();
  double d = std::hypot(a.x - b.x, a.y - b.y);
  if (d <= kPlacement) return {};
  char bx[kMaxNumberChars], by[kMaxNumberChars], ax[kMaxNumberChars], ay[kMaxNumberChars], dd[kMaxNumberChars];
  return fmt::format(
      "{} does not lie where the input prints: its part is centred at X{} Y{}, the input's at X{} Y{} ({} mm "
      "apart); slice it for the same printer and placement",
      their_name, number_text(b.x, 3, bx), number_text(b.y, 3, by), number_text(a.x, 3, ax), number_text(a.y, 3, ay),
      number_text(d, 1, dd));
}

SpliceBlock layer_index_block(const LayerIndex& index, int first, int last, bool through_end) {
  const IndexedLayer& l = index.layer(first);
  SpliceBlock b;
  b.fd = index.fd();
  b.name = index.name();
  b.markers = &index.markers();
  b.begin = l.info.offset;
  b.end = through_end ? std::uint64_t(-1) : index.layer(last).end;
  b.through_end = through_end;
  b.first_line = l.info.first_line;
  b.first_layer = l.info;
  b.start = index.point(first);
  return b;
}

// The block pipeline's one stage: rewrites the block's lines and hands them
// to the sink, keeping the printed side up to date.
class BlockStream::Bridge : public Stage {
 public:
  Bridge(BlockStream& owner, int prelude_lines, double retracted)
      : owner_(owner), pipeline_(*owner.block_.markers), prelude_(static_cast<std::uint64_t>(prelude_lines)) {
    pipeline_.add(*this);
    // The file's own retraction where the block starts.
    Move m;
    m.kind = MoveKind::Linear;
    m.filament = -retracted;
    retraction_.observe(m);
  }
  Pipeline& pipeline() { return pipeline_; }
  void set_sink(SpliceSink* sink) { sink_ = sink; }
  SpliceRewrite& rewrite() { return rewrite_; }
  const RetractionTracker& retraction() const { return retraction_; }

  void line(const TrackedLine& t, Emitter&) override {
    if (t.raw.number <= prelude_) return;
    StreamPoint& p = owner_.printed_;
    retraction_.observe(t.move);
    if (CarriedSettings::may_set(t.line)) p.settings.observe(t.line, t.before.tool);
    if (t.line.is_m(82) || t.line.is_m(83)) p.e_mode_set = true;
    if (t.move.extruding) {
      p.top_z = std::max(p.top_z, t.move.end[kZ] + rewrite_.z_shift().to_double());
      if (t.region == Region::Layer) {
        p.extent.add(t.move.start[kX], t.move.start[kY]);
        p.extent.add(t.move.end[kX], t.move.end[kY]);
      }
    }
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
  RetractionTracker retraction_;
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
  printed_.retracted = bridge_->retraction().pending();
}

}  // namespace gcode

namespace gcode {

// ---------------------------------------------------------------------------
// SpliceStage

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
  main_retraction_.observe(t.move);
  if (CarriedSettings::may_set(t.line)) main_settings_.observe(t.line, t.before.tool);
  if (t.line.kind == CommandKind::Standard && t.line.letter == 'M' && (t.line.number == 82 || t.line.number == 83))
    main_e_mode_set_ = true;
  if (t.origin == LineOrigin::Input) main_bytes_ = t.raw.offset + t.raw.size();
}

StreamPoint SpliceStage::main_point(const MachineState& before) const {
  StreamPoint p;
  p.state = before;
  p.retracted = main_retraction_.pending();
  p.settings = main_settings_;
  p.e_mode_set = main_e_mode_set_;
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
  printed_.retracted = main_retraction_.pending();
  printed_.settings = main_settings_;
  printed_.e_mode_set = main_e_mode_set_;
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
    Move m = printed_.state.apply(line);
    main_retraction_lead_.observe(m);
    if (CarriedSettings::may_set(line)) printed_.settings.observe(line, printed_.state.tool);
    if (line.is_m(82) || line.is_m(83)) printed_.e_mode_set = true;
  }
  printed_.retracted = main_retraction_lead_.pending();
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
  if (t.move.extruding) {
    printed_.top_z = std::max(printed_.top_z, t.move.end[kZ] + shift_.to_double());
    if (t.region == Region::Layer) {
      printed_.extent.add(t.move.start[kX], t.move.start[kY]);
      printed_.extent.add(t.move.end[kX], t.move.end[kY]);
    }
  }
}

}  // namespace gcode
