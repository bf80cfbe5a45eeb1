#include "gcode/serial/job/send_session.hpp"

#include <poll.h>
#include <signal.h>
#include <sys/signalfd.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <system_error>

#include <fmt/format.h>

#include "gcode/core/line.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/serial/control/control_verbs.hpp"
#include "gcode/serial/protocol/protocol.hpp"

namespace gcode::serial {

namespace {

constexpr std::size_t kReadSize = 65536;   // bytes read from the input at once
constexpr std::size_t kLowWater = 16384;   // read more when less is buffered

}  // namespace

// A swapped-in file: its text, and the pipeline that reads it as the
// printer's stream goes on.
struct SendSession::Segment : Stage {
  Segment(SendSession& session, std::unique_ptr<JoinStream> next, int layers_done, std::uint64_t lines_before)
      : session(session),
        source(std::move(next)),
        pipeline(source->markers(), PipelineOptions{.layers = true, .block_size = 16384}),
        layer_offset(layers_done),
        line_offset(lines_before) {
    pipeline.start_from(source->printed().state);
  }
  void line(const TrackedLine& t, Emitter&) override {
    if (session.current_ == this) session.deliver(t, layer_offset, line_offset);
  }
  void layer(const LayerInfo& info, const MachineState& before, Emitter&) override {
    if (session.current_ != this) return;
    LayerInfo i = info;
    i.index += layer_offset;
    i.first_line += line_offset;
    session.control_->layer(i, before, EventLoop::now());
  }
  void end_code(const EndCodeInfo&, const MachineState& before, Emitter&) override {
    if (session.current_ == this) session.control_->end_code(before, EventLoop::now());
  }
  bool reads_state() const override { return true; }

  SendSession& session;
  std::unique_ptr<JoinStream> source;
  Pipeline pipeline;
  int layer_offset;
  std::uint64_t line_offset;
  std::string text;       // pumped from the source, not fed yet
  std::size_t pos = 0;
  bool source_done = false;
};

SendSession::SendSession(EventLoop& loop, Sender& sender, int input_fd, int port_fd, Diagnostics& diagnostics,
                         LayerMarkers markers)
    : loop_(loop),
      sender_(sender),
      input_fd_(input_fd),
      port_fd_(port_fd),
      diag_(diagnostics),
      markers_(std::move(markers)),
      pipeline_(markers_, PipelineOptions{.layers = true, .block_size = 16384}) {
  set_nonblocking(port_fd_);
  struct stat st{};
  if (::fstat(input_fd_, &st) == 0 && S_ISREG(st.st_mode)) input_size_ = static_cast<std::uint64_t>(st.st_size);
  sigset_t mask;
  sigemptyset(&mask);
  sigaddset(&mask, SIGINT);
  sigaddset(&mask, SIGTERM);
  sigprocmask(SIG_BLOCK, &mask, &saved_mask_);
  signal_fd_ = signalfd(-1, &mask, SFD_CLOEXEC | SFD_NONBLOCK);
  if (signal_fd_ >= 0) loop_.add_fd(signal_fd_, POLLIN, [this](short) { on_signal(); });
  watch_port();
  loop_.add_timer([this] { return sender_.deadline(); },
                  [this](double now) {
                    sender_.on_timer(now);
                    update();
                  });
}

void SendSession::watch_port() {
  port_watch_ = loop_.add_fd(port_fd_, POLLIN, [this](short revents) {
    if (revents & (POLLIN | POLLHUP | POLLERR)) read_port();
    update();
  });
}

SendSession::~SendSession() {
  if (signal_fd_ >= 0) ::close(signal_fd_);
  if (port_replaced_ && port_fd_ >= 0) ::close(port_fd_);
  // Back to the mask the caller had (a signal it blocked itself stays blocked).
  sigprocmask(SIG_SETMASK, &saved_mask_, nullptr);
}

PrintArea SendSession::read_print_area() {
  PrintArea area;
  if (scan_file_limits(input_fd_, area)) return area;
  return scan_text_limits(pipeline_.read_header(input_fd_));
}

int SendSession::read_e_mode(EModeChoice choice, std::string_view name) {
  EModeReading reading = read_e_mode_of(input_fd_, choice, name, [&] { return pipeline_.read_header(input_fd_); });
  if (reading.file_sets_mode) return -1;
  if (!reading.warning.empty()) diag_.warn(reading.warning);
  pipeline_.set_e_mode(reading.relative);
  return reading.relative ? 1 : 0;
}

void SendSession::set_control(const PrintControlConfig& config, const std::string& control_path) {
  control_ = std::make_unique<PrintControl>(config, sender_, diag_, pipeline_.precision());
  if (resumed_layer_ > 0) control_->continue_in_layer(resumed_layer_);
  if (line_base_ > 0) control_->objects().continue_from(printed_objects_.tracker());
  sender_.set_action_handler([this](std::string_view action) { control_->action(action, EventLoop::now()); });
  sender_.set_lost_handler([this](std::string_view why) { control_->lost(why, EventLoop::now()); });
  control_->on_status = [this] {
    if (progress_) progress_->print_line(snapshot());
  };
  control_->on_swap = [this](std::unique_ptr<JoinStream> next, int layers_done) {
    start_swap(std::move(next), layers_done);
  };
  if (control_path.empty()) return;
  fifo_ = std::make_unique<ControlFifo>(control_path);
  parser_ = std::make_unique<ControlParser>([this](const ControlCommand& c) { control_->command(c, EventLoop::now()); },
                                            [this](std::string_view why) { diag_.warn(0, why); });
  loop_.add_fd(fifo_->fd(), POLLIN, [this](short) {
    fifo_->read_into(*parser_);
    update();
  });
}

void SendSession::set_journal(SendJournal* journal) {
  journal_ = journal;
  if (journal_ == nullptr) return;
  sender_.set_journal_hooks(
      [this](const Sender::Numbered& c) {
        // A pause block is numbered inside the control's call: its lines
        // carry the pause state it set.
        note_live_control();
        journal_->numbered(c);
      },
      [this](long long n) { journal_->acknowledged(n); });
  // At least once a second, whether or not anything else happens.
  journal_due_ = EventLoop::now();
  loop_.add_timer([this] { return journal_due_; },
                  [this](double now) {
                    journal_->flush(now);
                    journal_due_ = journal_->next_sync(now);
                  });
}

void SendSession::hash_fed(std::string_view bytes) {
  if (input_hash_.fed(bytes)) journal_->checkpoint(input_hash_.bytes(), input_hash_.digest());
}

void SendSession::skip_printed(std::uint64_t bytes, std::uint64_t hash_bytes, std::uint64_t lines, int layer,
                               const MachineState& state) {
  LayerMarkerSearch markers(markers_);
  std::string block(kReadSize, '\0');
  const std::uint64_t need = std::max(bytes, hash_bytes);
  std::uint64_t done = 0;
  while (done < need) {
    ssize_t n = ::read(input_fd_, block.data(), block.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw std::runtime_error(fmt::format("cannot read the input: {}", std::strerror(errno)));
    if (n == 0) break;
    std::string_view got(block.data(), static_cast<std::size_t>(n));
    if (done < bytes) {
      // The printed part: hashed as if it had been fed, not fed; the check's
      // digest taken where the journal's checkpoint is.
      auto printed = static_cast<std::size_t>(std::min<std::uint64_t>(bytes - done, got.size()));
      std::string_view part = got.substr(0, printed);
      markers.feed(part);
      printed_objects_.feed(part);
      input_hash_.printed(part, hash_bytes);
      got.remove_prefix(printed);
    }
    in_buf_.append(got);
    done += static_cast<std::uint64_t>(n);
  }
  input_hash_.printed_end(in_buf_, hash_bytes, done >= hash_bytes);
  skipped_bytes_ = input_hash_.bytes();
  input_bytes_ = skipped_bytes_;
  line_base_ = lines;
  layer_base_ = layer;
  resumed_layer_ = layer;
  resumed_z_ = state.lifted ? state.lift_base_z : state.position[kZ];
  pipeline_.start_from(state);
  // Inside the print's layers its pipeline knows how they are marked from
  // the printed part: left to find out, it held every line up to the next
  // marker (a whole layer, several in a file without markers), which then
  // went to the sender in one batch, numbered far ahead of the printer: a
  // printer reset in it found the way back no longer held.
  if (layer > 0) pipeline_.decide_layer_mode(markers.found() ? LayerMode::Markers : LayerMode::Heuristic);
}

// What read_print_area read of a stream into the pipeline goes to the
// printer with the first line fed: its bytes and lines count as fed.
void SendSession::count_header() {
  std::string_view head = pipeline_.buffered();
  if (journal_ != nullptr) hash_fed(head);
  for (std::size_t pos = 0, nl; (nl = head.find('\n', pos)) != std::string_view::npos; pos = nl + 1) {
    ++fed_lines_;
    if (journal_ != nullptr) journal_->line_end(line_base_ + fed_lines_, input_bytes_ + nl + 1);
  }
  input_bytes_ += head.size();
}

void SendSession::run() {
  if (!control_) set_control(PrintControlConfig{}, std::string());
  control_->add_stages(pipeline_, line_base_, resumed_layer_);
  pipeline_.add(*this);
  count_header();
  input_watch_ = loop_.add_fd(input_fd_, POLLIN, [this](short) { read_input(); });
  started_ = EventLoop::now();
  if (progress_) {
    loop_.add_timer([this] { return next_report_; }, [this](double) { report(false); });
  }
  sender_.start(EventLoop::now());
  update();
  if (!loop_.stopped()) loop_.run();
  if (progress_) report(true);
}

// The input's pipeline: nothing of it goes on once a swap left it.
void SendSession::line(const TrackedLine& t, Emitter&) {
  if (current_ != nullptr) return;
  deliver(t, layer_base_, line_base_, resumed_layer_);
}

// A resume's pipeline starts inside a layer without its marker: in a file
// whose next marker does not come (the last layer, a cut file) it falls
// back to finding layers by height, and its first is the layer the print
// stopped in, at the height the nozzle stood at. That one is not counted
// again. (A marker's layer lies above it.)
bool SendSession::same_layer_again(const LayerInfo& info) {
  if (resumed_layer_ <= 0 || info.index != 1) return false;
  if (layer_base_ != resumed_layer_ || std::abs(info.z - resumed_z_) > 1e-3) return false;
  --layer_base_;
  return true;
}

void SendSession::layer(const LayerInfo& info, const MachineState& before, Emitter&) {
  if (current_ != nullptr) return;
  if (journal_ != nullptr) {
    journal_->checkpoint(input_hash_.bytes(), input_hash_.digest());
    journal_->layer_began();
  }
  if (same_layer_again(info)) return;
  LayerInfo shifted = info;
  shifted.index += layer_base_;
  shifted.first_line += line_base_;
  control_->layer(shifted, before, EventLoop::now());
}

void SendSession::end_code(const EndCodeInfo&, const MachineState& before, Emitter&) {
  if (current_ == nullptr) control_->end_code(before, EventLoop::now());
}

// A swapped-in file's lines count on from what was printed before it.
// `resumed_layer`: a resume's input, whose pipeline starts inside layer
// `resumed_layer` (the journal's) and takes the lines before the next layer
// for start code: they are of that layer (the progress, a reset's warning,
// the journal, where a pause goes).
void SendSession::deliver(const TrackedLine& t, int layer_offset, std::uint64_t line_offset, int resumed_layer) {
  ++input_lines_;
  if (layer_offset == 0 && line_offset == 0) {
    control_->line(t, EventLoop::now());
    return;
  }
  RawLine raw = t.raw;
  raw.number += line_offset;
  const bool before_next_layer = t.layer == 0 && resumed_layer > 0;
  TrackedLine shifted{raw,
                      t.line,
                      t.move,
                      t.before,
                      t.state,
                      before_next_layer ? Region::Layer : t.region,
                      t.layer > 0 ? t.layer + layer_offset : resumed_layer,
                      t.feature,
                      t.origin};
  control_->line(shifted, EventLoop::now());
}

int SendSession::layers() const {
  if (current_ != nullptr) return current_->layer_offset + current_->pipeline.tracker().layer_count();
  return pipeline_.tracker().layer_count();
}

void SendSession::start_swap(std::unique_ptr<JoinStream> next, int layers_done) {
  segments_.push_back(std::make_unique<Segment>(*this, std::move(next), layers_done, input_lines_));
  current_ = segments_.back().get();
  control_->add_stages(current_->pipeline, current_->line_offset);
  current_->pipeline.add(*current_);
  // The layers and time to come are the other file's: as far as known.
  total_layers_ = 0;
  eta_.set_estimate(0);
  // The input is read no further.
  if (input_watch_ >= 0) loop_.set_events(input_watch_, 0);
}

// One line of the swapped-in file; false when none is ready.
bool SendSession::feed_segment() {
  Segment& s = *current_;
  if (s.pos == s.text.size()) {
    s.text.clear();
    s.pos = 0;
    if (!s.source_done && !s.source->pump(s.text, control_->seam_options(), pipeline_.precision(), &diag_))
      s.source_done = true;
    if (s.text.empty()) {
      s.pipeline.finish();
      input_done_ = true;
      control_->end_of_input(EventLoop::now());
      return false;
    }
  }
  std::size_t nl = s.text.find('\n', s.pos);
  std::size_t end = nl == std::string::npos ? s.text.size() : nl + 1;
  s.pipeline.feed(std::string_view(s.text).substr(s.pos, end - s.pos));
  s.pos = end;
  sender_.pump(EventLoop::now());
  return true;
}

void SendSession::read_input() {
  if (in_pos_ > 0 && in_pos_ == in_buf_.size()) {
    in_buf_.clear();
    in_pos_ = 0;
  } else if (in_pos_ > kLowWater) {
    in_buf_.erase(0, in_pos_);
    in_pos_ = 0;
  }
  std::size_t old = in_buf_.size();
  in_buf_.resize(old + kReadSize);
  ssize_t n;
  do {
    n = ::read(input_fd_, in_buf_.data() + old, kReadSize);
  } while (n < 0 && errno == EINTR);
  if (n < 0) {
    in_buf_.resize(old);
    if (errno == EAGAIN) return;
    throw std::runtime_error(fmt::format("cannot read the input: {}", std::strerror(errno)));
  }
  in_buf_.resize(old + static_cast<std::size_t>(n));
  if (n == 0) input_eof_ = true;
  update();
}

// One line at a time, while the sender and the control take more.
void SendSession::feed_input() {
  while (!input_done_ && control_->accepts_input() && sender_.wants_input()) {
    if (current_ != nullptr) {
      if (!feed_segment()) break;
      continue;
    }
    if (in_pos_ == in_buf_.size() && !input_eof_) break;
    std::size_t nl = in_buf_.find('\n', in_pos_);
    if (nl == std::string::npos) {
      if (!input_eof_) break;
      if (in_pos_ < in_buf_.size()) {
        // A last line without a newline.
        if (journal_ != nullptr) {
          hash_fed(std::string_view(in_buf_).substr(in_pos_));
          journal_->line_end(line_base_ + ++fed_lines_, in_buf_.size() - in_pos_ + input_bytes_);
        }
        pipeline_.feed(std::string_view(in_buf_).substr(in_pos_));
        input_bytes_ += in_buf_.size() - in_pos_;
        in_pos_ = in_buf_.size();
      }
      pipeline_.finish();
      input_done_ = true;
      control_->end_of_input(EventLoop::now());
      break;
    }
    std::string_view fed = std::string_view(in_buf_).substr(in_pos_, nl + 1 - in_pos_);
    // Where each line ends, by count (a stage may rewrite a line's text),
    // known before the line can reach the sender.
    ++fed_lines_;
    if (journal_ != nullptr) {
      hash_fed(fed);
      journal_->line_end(line_base_ + fed_lines_, input_bytes_ + fed.size());
    }
    pipeline_.feed(fed);
    input_bytes_ += nl + 1 - in_pos_;
    in_pos_ = nl + 1;
    // Out at once if the flow control allows: the sender holds only a line
    // or two that is not on its way yet.
    sender_.pump(EventLoop::now());
  }
  if (input_done_ && control_->input_may_end()) sender_.end_of_input();
}

void SendSession::read_port() {
  char buf[4096];
  for (;;) {
    ssize_t n = ::read(port_fd_, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno == EAGAIN) break;
    if (n <= 0) {
      port_lost(n == 0 ? "end of file" : std::strerror(errno));
      return;
    }
    double now = EventLoop::now();
    port_in_.append(buf, static_cast<std::size_t>(n));
    std::size_t pos = 0;
    for (std::size_t nl; (nl = port_in_.find('\n', pos)) != std::string::npos; pos = nl + 1) {
      std::string_view line = std::string_view(port_in_).substr(pos, nl - pos);
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      sender_.on_line(line, now);
    }
    port_in_.erase(0, pos);
    if (port_in_.size() > 4096) port_in_.clear();  // no newline in 4 KB: line noise
    // A short read took all there was: the next poll() says when more
    // comes (one read a turn, not a second that finds nothing).
    if (static_cast<std::size_t>(n) < sizeof buf) break;
  }
}

void SendSession::flush_port() {
  // Every command's record goes to the journal before its bytes go out.
  if (journal_ != nullptr && !sender_.output().empty()) journal_->flush(EventLoop::now());
  while (port_watch_ >= 0 && !sender_.output().empty()) {
    std::string_view out = sender_.output();
    ssize_t n = ::write(port_fd_, out.data(), out.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno == EAGAIN) break;
    if (n < 0) {
      port_lost(std::strerror(errno));
      return;
    }
    sender_.written(static_cast<std::size_t>(n), EventLoop::now());
  }
}

void SendSession::set_reconnect(const std::string& path, const PortOptions& options, double seconds) {
  reconnect_.emplace(sender_, diag_, path, options, seconds);
  loop_.add_timer([this] { return reconnect_->next_try(); },
                  [this](double now) {
                    try_reconnect(now);
                    update();
                  });
}

std::string_view SendSession::state_label() const {
  if (sender_.state() == SenderState::Failed) return "failed";
  if (sender_.emergency()) return "stopped";
  // (A cancelled print ends with its safe end sent: "cancelled", not done.)
  if (sender_.finished()) return control_->cancelled() ? "cancelled" : "done";
  if (reconnecting()) return "reconnecting";
  return control_->state_label();
}

void SendSession::port_lost(std::string_view why) {
  if (port_watch_ >= 0) {
    loop_.set_events(port_watch_, 0);
    loop_.remove_fd(port_watch_);
    port_watch_ = -1;
  }
  if (!reconnect_) {
    sender_.disconnected(why);
    return;
  }
  if (!reconnect_->lost(why, EventLoop::now())) return;
  ::close(port_fd_);
  port_fd_ = -1;
  port_replaced_ = true;
  port_in_.clear();
}

void SendSession::try_reconnect(double now) {
  const int fd = reconnect_->attempt(now);
  if (fd < 0) return;
  port_fd_ = fd;
  watch_port();
}

void SendSession::on_signal() {
  signalfd_siginfo info{};
  while (::read(signal_fd_, &info, sizeof info) == static_cast<ssize_t>(sizeof info)) {
    ++interrupts_;
    if (reconnecting()) {
      reconnect_->give_up("interrupted while waiting for the port to come back: nothing more was sent");
      continue;
    }
    if (interrupts_ == 1 && control_->interrupt()) continue;
    if (!sender_.emergency()) {
      diag_.error("emergency stop: M112 sent");
      sender_.emergency_stop();
    }
  }
  update();
}

ProgressSnapshot SendSession::snapshot() const {
  ProgressSnapshot s;
  const SenderStats& st = sender_.stats();
  s.state = state_label();
  s.layer = control_->layer();
  s.layers = std::max(total_layers_, layers());
  if (current_ != nullptr) {
    const JoinStream& j = *current_->source;
    if (j.bytes() > 0) s.percent = 100.0 * static_cast<double>(j.bytes_out()) / static_cast<double>(j.bytes());
  } else if (input_size_ > 0) {
    s.percent = 100.0 * static_cast<double>(input_bytes_) / static_cast<double>(input_size_);
  }
  s.lines = st.lines;
  const double now = EventLoop::now();
  s.elapsed = st.print_start >= 0 ? now - st.print_start : 0;
  s.lines_per_second = s.elapsed > 0 ? static_cast<double>(st.lines) / s.elapsed : 0;
  s.eta = eta_.remaining(now, sender_.estimated_time(), control_->paused_seconds(now), s.percent, s.elapsed);
  s.speed = control_->speed();
  s.temperatures = sender_.temperatures();
  s.objects = control_->objects().json();
  s.resets = static_cast<int>(st.resets);
  s.redone_mm = st.redone_mm;
  s.pauses = static_cast<int>(control_->pauses().size());
  if (!control_->pauses().empty()) {
    s.last_pause_mm = control_->pauses().back().latency_mm;
    s.last_pause_s = control_->pauses().back().latency_s;
    s.last_pause_layer = control_->pauses().back().layer;
    s.last_paused_before = control_->pauses().back().paused_before_layer;
  }
  return s;
}

void SendSession::report(bool force) {
  double now = EventLoop::now();
  progress_->report(snapshot(), now, force);
  next_report_ = now + progress_->interval();
}

void SendSession::note_live_control() {
  if (journal_ == nullptr || control_ == nullptr) return;
  LiveControl live;
  for (const ControlVerb& verb : control_verbs())
    if (!verb.journal_field.empty()) live.kept.emplace_back(verb.journal_field, verb.journal(*control_));
  live.state = control_->state_label();
  live.paused = control_->state() == PrintState::Paused;
  journal_->live(live);
}

void SendSession::update() {
  note_live_control();
  feed_input();
  sender_.pump(EventLoop::now());
  flush_port();
  control_->update(EventLoop::now());
  if (!eta_.pacing() && control_->layer() >= 1) {
    const double now = EventLoop::now();
    eta_.layer_one(now, sender_.estimated_time(), control_->paused_seconds(now));
  }
  if (reconnecting() && control_->cancelled()) {
    // Nobody to send the safe end to: the print stops where the printer is.
    reconnect_->give_up("cancelled while waiting for the port to come back: nothing more was sent");
  }
  if (progress_ && (state_label() != shown_state_ || control_->layer() != shown_layer_)) {
    shown_state_ = state_label();
    shown_layer_ = control_->layer();
    progress_->report(snapshot(), EventLoop::now(), false);
  }
  if (sender_.finished() && sender_.output().empty()) {
    loop_.stop();
    return;
  }
  if (port_watch_ >= 0)
    loop_.set_events(port_watch_, static_cast<short>(POLLIN | (sender_.output().empty() ? 0 : POLLOUT)));
  bool want = current_ == nullptr && !input_eof_ && in_buf_.size() - in_pos_ < kLowWater;
  if (input_watch_ >= 0) loop_.set_events(input_watch_, want ? POLLIN : 0);
}

}  // namespace gcode::serial
