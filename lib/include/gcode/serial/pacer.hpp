#pragma once
// Pacing (SenderConfig::pace): hold no more moves ahead of the nozzle than
// the printer's planner takes, and follow the printer's real pace, so the
// planner is never held back while it runs dry. A move goes out only while
// the moves in flight and those the planner still holds are fewer than its
// blocks; what the planner holds is a model, corrected by what the printer
// says:
//  * each answered move entered the planner then and runs for its length
//    at its feed rate divided by the printer's speed factor (pace_rate.hpp)
//    after the one before;
//  * a planner of n blocks took move m only when move m - n had ended: an
//    answer that came as soon as the move arrived says that block had ended
//    by then (the model's end times are pulled back to it), one that came
//    later (the move waited for a block) says when it ended: a sighting,
//    which sets the model's clock and teaches the speed factor;
//  * ADVANCED_OK's P (free blocks) says how many moves the planner holds
//    at every answer: a sighting each time;
//  * a command that waits (M109, G28, M400) or "busy:" holds the printer
//    for reasons other than its moves: a late answer after it is no
//    sighting.
// Without ADVANCED_OK a full planner is the only way to see it run: when no
// move has waited for a while the pacer sends one move more than the model
// says fits (a probe), timed to reach the printer just before the model's
// next block ends. If it waits, its answer is a sighting; if it finds room,
// the printer is faster than the model and the speed factor grows.
#include <algorithm>
#include <array>
#include <cstddef>

#include "gcode/serial/pace_rate.hpp"

namespace gcode::serial {

class Pacer {
 public:
  static constexpr double kNever = 1e300;
  static constexpr double kUnknown = 1e300;     // a move's arrival, not known
  static constexpr std::size_t kMaxBlocks = 64;
  static constexpr long long kProbeEvery = 24;  // answered moves without a sighting before a probe
  static constexpr double kGrace = 0.25;        // of a block: how late an answer is before it waited
  static constexpr double kProbeLead = 0.5;     // of a block: how long before its end a probe arrives

  // A move `number` may go, `lead` seconds from its arrival (the link's
  // time for it), with `moves_in_flight` sent and not answered and a
  // planner of `planner_blocks`? When it must wait and nothing is in flight
  // (no answer will come), wake() says when it may go.
  bool blocked(double now, int moves_in_flight, long long number, double lead, int planner_blocks);

  struct Answer {
    long long number = 0;        // the move's line number
    double nominal = 0;          // printer seconds at the file's feed rate
    double now = 0;              // when its "ok" came
    double arrival = kUnknown;   // when its last byte reached the printer
    int planner_free = -1;       // ADVANCED_OK's P, -1 when not said
  };
  void answered(const Answer& a, int planner_blocks, double time_scale);
  // An answered command that is not a move; `waits`: one that may hold the
  // queue for reasons other than the planner's room (M109, G28, G4, M400).
  void answered_other(bool waits);
  // "busy:" or a heating report: the printer is held.
  void interrupted();

  // When a blocked move may go (kNever: with an answer).
  double wake() const { return wake_; }
  void clear_wake() { wake_ = kNever; }
  // What the model believes of the printer's pace (pace_rate.hpp).
  double speed_factor() const { return rate_.factor(); }
  // Moves the model says the planner still holds at `now`.
  int ahead(double now, int planner_blocks) const;

 private:
  static constexpr std::size_t kHistory = 128;  // answered moves kept (a sample spans at most these)
  struct Planned {
    double entered;   // when it was answered
    double seconds;   // its length at its feed rate, in the sender's seconds
    double end;       // when the model says it ends
  };
  std::size_t blocks(int planner_blocks) const;
  // Move `index` (a count of answered moves), kept while newer than oldest().
  Planned& move(long long index) { return ring_[static_cast<std::size_t>(index) % kHistory]; }
  const Planned& move(long long index) const { return ring_[static_cast<std::size_t>(index) % kHistory]; }
  long long oldest() const { return std::max(answered_ - static_cast<long long>(kHistory) + 1, 1LL); }
  const Planned* next_to_end(double now, int planner_blocks) const;
  bool probe_due() const { return probe_ < 0 && since_sighting_ >= kProbeEvery && answered_ > 0; }
  bool observe(long long freed, double entered, double late, bool bounded);
  void sight(long long index, double t);
  double end_with(long long from, double start, long long to, double factor) const;
  void chain();

  std::array<Planned, kHistory> ring_{};
  long long answered_ = 0;      // moves answered; the newest is move(answered_)
  long long known_ = 0;         // moves up to this one are known to have ended,
  double anchor_ = -kNever;     // the last of them then
  long long sighted_ = -1;      // the move whose end was last sighted,
  double sighted_at_ = 0;       // then

  double base_ = kNever;         // the least answer minus arrival: the host's own latency
  double jitter_ = 0;           // how late answers that did not wait came, on average
  bool clean_ = true;           // nothing but moves (or instant commands) since the last move
  long long probe_ = -1;        // the line number of a probe not answered yet
  long long since_sighting_ = 0;
  double wake_ = kNever;
  PaceRate rate_;
};

}  // namespace gcode::serial
