#include "gcode/serial/protocol/answer_clock.hpp"

#include <algorithm>

namespace gcode::serial {

namespace {

constexpr double kReplyBytes = 64;  // an "ok T:..." line, more than an "ok"

}  // namespace

AnswerClock::AnswerClock(double bytes_per_second, double time_scale, int planner_blocks) {
  set_link(bytes_per_second, time_scale);
  set_planner_blocks(planner_blocks);
}

void AnswerClock::set_link(double bytes_per_second, double time_scale) {
  byte_time_ = bytes_per_second > 0 ? 1 / bytes_per_second : 0;
  scale_ = time_scale > 0 ? time_scale : 1;
}

void AnswerClock::set_planner_blocks(int blocks) {
  std::size_t n = static_cast<std::size_t>(std::clamp(blocks, 1, static_cast<int>(kMaxPlanner)));
  if (n == planner_) return;
  // Keep the newest moves that still fit, oldest first.
  std::size_t keep = std::min(n, count_);
  std::array<double, kMaxPlanner> ends{};
  std::array<double, kMaxPlanner> estimates{};
  for (std::size_t i = 0; i < keep; ++i) {
    std::size_t from = (next_ + planner_ - 1 - i) % planner_;
    ends[keep - 1 - i] = ends_[from];
    estimates[keep - 1 - i] = estimates_[from];
  }
  ends_ = ends;
  estimates_ = estimates;
  count_ = keep;
  next_ = keep % n;
  planner_ = n;
}

double AnswerClock::written(std::size_t bytes, double now) {
  wire_free_ = std::max(wire_free_, now) + static_cast<double>(bytes) * byte_time_;
  return wire_free_;
}

void AnswerClock::answered(double motion, double now, double nominal) {
  last_answer_ = now;
  if (motion <= 0) return;
  if (count_ == planner_) {
    // This move got the block of the one `planner_` moves back: that block
    // took at most the time since the last move was answered.
    if (estimates_[next_] > 0) {
      double taken = (now - last_move_answer_) * scale_;
      double measured = 0;
      double estimated = 0;
      taken_[sample_next_] = taken;
      estimated_[sample_next_] = estimates_[next_];
      sample_next_ = (sample_next_ + 1) % kSamples;
      samples_ = std::min(samples_ + 1, kSamples);
      for (std::size_t i = 0; i < samples_; ++i) {
        measured += taken_[i];
        estimated += estimated_[i];
      }
      // Quick to believe the printer slower, slow to believe it faster: a
      // short burst of answers (after a resend) says little about its moves.
      double sample = estimates_[next_] > 0 ? 1.25 * taken / estimates_[next_] : 0;
      double window = samples_ >= 4 ? 1.25 * measured / estimated : kMotionFactor;
      factor_ = std::clamp(std::max(window, std::min(sample, kMotionFactor)), kMinFactor, kMotionFactor);
    }
    // And it had ended by now: if the model says later, its times run long.
    double late = ends_[next_] - now;
    if (late > 0) {
      for (std::size_t i = 0; i < count_; ++i) ends_[i] -= late;
      last_end_ -= late;
    }
  } else {
    ++count_;
  }
  last_move_answer_ = now;
  last_end_ = std::max(last_end_, now) + std::max(motion * factor_, nominal) / scale_;
  ends_[next_] = last_end_;
  estimates_[next_] = motion;
  next_ = (next_ + 1) % planner_;
}

void AnswerClock::keepalive(double now) {
  double gap = now - last_keepalive_;
  // Gaps longer than a few intervals lie between two long commands.
  if (gap > 0 && gap < 4 * kKeepalive / scale_)
    keepalive_interval_ = keepalive_interval_ > 0 ? (keepalive_interval_ + gap) / 2 : gap;
  last_keepalive_ = now;
}

double AnswerClock::ready(double arrival, const Wait& wait) const {
  double t = std::max(arrival, last_answer_);
  double ahead = wait.motion * factor_ / scale_;
  if (wait.empty) {
    t = std::max(t, std::max(last_end_, last_answer_) + ahead);
  } else if (wait.moves > 0) {
    // Room for `moves` more blocks: when the block that many back from the
    // newest has ended (no wait while fewer moves were answered).
    auto back = static_cast<std::size_t>(wait.moves);
    if (back > planner_) {
      t = std::max(t, std::max(last_end_, last_answer_) + ahead);
    } else if (planner_ - back < count_) {
      std::size_t oldest = count_ == planner_ ? next_ : 0;
      t = std::max(t, ends_[(oldest + (count_ - 1 - (planner_ - back)) ) % planner_]);
    }
  }
  return t;
}

double AnswerClock::due(double arrival, const Wait& wait) const {
  double t = ready(arrival, wait);
  if (wait.unbounded || last_keepalive_ > last_answer_) {
    double interval = keepalive_interval_ > 0 ? keepalive_interval_ : kKeepalive / scale_;
    t = std::max(t, std::max({last_keepalive_, arrival, last_answer_}) + 1.5 * interval);
  }
  return t + margin();
}

double AnswerClock::quiet(std::size_t bytes) const {
  if (byte_time_ <= 0) return 0.02;
  return std::clamp(2 * (static_cast<double>(bytes) + kReplyBytes) * byte_time_, 0.002, 0.5);
}

double AnswerClock::margin() const { return kMargin + kReplyBytes * byte_time_; }

}  // namespace gcode::serial
