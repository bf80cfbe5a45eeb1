#include "gcode/serial/job/progress.hpp"

#include <algorithm>

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>

#include <fmt/format.h>

namespace gcode::serial {

namespace {

std::string clock_text(double seconds) {
  long long s = static_cast<long long>(seconds + 0.5);
  if (s >= 3600) return fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60);
  return fmt::format("{}:{:02}", s / 60, s % 60);
}

}  // namespace

double estimated_remaining(double estimated_total, double estimated_done, double printing_seconds) {
  if (estimated_total <= 0 || estimated_done < 0.05 * estimated_total || printing_seconds < 5) return -1;
  const double pace = printing_seconds / estimated_done;
  return std::max(0.0, estimated_total - estimated_done) * pace;
}

void PrintEta::layer_one(double now, double estimated_done, double paused) {
  if (pacing()) return;
  origin_wall_ = now;
  origin_estimate_ = estimated_done;
  origin_paused_ = paused;
}

double PrintEta::remaining(double now, double estimated_done, double paused, double percent, double elapsed) const {
  double eta = -1;
  if (pacing())
    eta = estimated_remaining(estimate_ - origin_estimate_, estimated_done - origin_estimate_,
                              now - origin_wall_ - (paused - origin_paused_));
  if (eta < 0 && percent > 1 && elapsed > 0) eta = elapsed * (100 - percent) / percent;
  return eta;
}

std::string progress_line(const ProgressSnapshot& s) {
  std::string line = fmt::format("{:<10}", s.state);
  if (s.layer > 0) {
    line += fmt::format(" layer {}", s.layer);
    if (s.layers > s.layer) line += fmt::format("/{}", s.layers);
  } else {
    line += " start code";
  }
  if (s.percent >= 0) line += fmt::format("  {:.1f} %", s.percent);
  line += fmt::format("  {} lines  {:.0f} lines/s  {} elapsed", s.lines, s.lines_per_second, clock_text(s.elapsed));
  if (s.eta >= 0) line += fmt::format("  ETA {}", clock_text(s.eta));
  if (s.speed != 1) line += fmt::format("  speed x{:g}", s.speed);
  if (!s.temperatures.empty()) line += fmt::format("  {}", s.temperatures);
  if (s.last_pause_mm >= 0) line += fmt::format("  last pause {:.1f} mm {:.2f} s", s.last_pause_mm, s.last_pause_s);
  if (s.resets > 0) line += fmt::format("  {} reset{} ({:.1f} mm again)", s.resets, s.resets > 1 ? "s" : "", s.redone_mm);
  return line;
}

std::string progress_json(const ProgressSnapshot& s) {
  auto num = [](double v) { return v < 0 ? std::string("null") : fmt::format("{:.3f}", v); };
  return fmt::format(
      "{{\"state\": \"{}\", \"layer\": {}, \"layers\": {}, \"percent\": {}, \"lines\": {}, \"lines_per_second\": {:.1f}, "
      "\"elapsed\": {:.3f}, \"eta\": {}, \"speed\": {:g}, \"pauses\": {}, \"last_pause_mm\": {}, \"last_pause_s\": {}, "
      "\"last_pause_layer\": {}, \"last_paused_before\": {}, \"resets\": {}, \"redone_mm\": {:.1f}, "
      "\"temperatures\": \"{}\"{}}}\n",
      s.state, s.layer, s.layers, num(s.percent), s.lines, s.lines_per_second, s.elapsed, num(s.eta), s.speed, s.pauses,
      num(s.last_pause_mm), num(s.last_pause_s), s.last_pause_layer, s.last_paused_before, s.resets, s.redone_mm,
      s.temperatures, s.objects.empty() ? std::string() : ", \"objects\": " + s.objects);
}

Progress::Progress(ProgressOptions options, Diagnostics& diagnostics)
    : options_(std::move(options)), diag_(diagnostics) {}

Progress::~Progress() {
  if (live_shown_) std::fputs("\n", stderr);
}

double Progress::interval() const { return options_.mode == ProgressMode::Live ? 0.25 : options_.interval; }

void Progress::print_line(const ProgressSnapshot& s) {
  if (live_shown_) std::fputs("\r\033[K", stderr);
  live_shown_ = false;
  diag_.report(progress_line(s));
}

void Progress::report(const ProgressSnapshot& s, double now, bool force) {
  bool changed = s.state != last_state_ || s.layer != last_layer_ || s.objects != last_objects_;
  if (!options_.status_file.empty() && (force || changed || now >= last_status_ + 1)) {
    write_status(s);
    last_status_ = now;
  }
  last_state_ = std::string(s.state);
  last_layer_ = s.layer;
  last_objects_ = s.objects;
  if (options_.mode == ProgressMode::Off) return;
  if (!force && now < last_line_ + interval()) return;
  last_line_ = now;
  if (options_.mode == ProgressMode::Live) {
    std::fprintf(stderr, "\r\033[K%s", progress_line(s).c_str());
    std::fflush(stderr);
    live_shown_ = true;
  } else {
    diag_.report(progress_line(s));
  }
}

void Progress::write_status(const ProgressSnapshot& s) {
  std::string tmp = options_.status_file + ".tmp";
  int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return;
  std::string text = progress_json(s);
  bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  ::close(fd);
  if (ok) ::rename(tmp.c_str(), options_.status_file.c_str());
}

}  // namespace gcode::serial
