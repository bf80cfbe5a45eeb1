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
// The factor rises only to a speed the printer has shown (a floor: what
// ran between a move's release and the answer that says its block had
// ended; host latency only lowers it), never on timing alone: at the file's
// speed a factor learnt too high held more moves in flight than the planner
// takes, and `pause now` stopped 3.5 mm on instead of 3.2. That floor is
// close to the printer's pace only when the planner was full, which
// ADVANCED_OK's P shows at every answer. Without it the pacer asks with a
// move of no length (a bare G1: no motion, no state), sent while the model
// says the planner is full (probe_wanted): Marlin waits for a free block
// before it drops such a move (FirmwareFlavor::empty_move_waits), so its ok
// says the oldest block the model holds had ended by then, and when it came
// late, that it ended then (a sighting). Either frees a block of the model
// without overfilling the planner (one move is released for it), so the
// moves go out at the printer's pace and the floor follows it. But the
// floor never shows more than the pacer lets go: a printer that drains its
// blocks faster than the link refills them (10 x at 250000 baud) or whose
// moves take no time would get one move per probe's round trip. So probes
// that keep finding room (answered within half a block, each sent right
// behind the moves the one before let go, or ahead of the last quarter of
// them), once the moves of a round trip ran, at the model's pace, in under
// twice its time (the link the limit, not the printer: until a probe says
// the planner was full), let more moves go past the model each time, 1, 2,
// 4 ... up to the planner's blocks; a late probe puts it back to one, a move
// that clearly waited for a block stops it until the next probe's answer
// (probe_credit.hpp). At the file's pace the planner is full and the
// probes come late. Moves go beyond the model only while fewer than
// kCreditInFlight are unanswered, so a bet that lost holds at most that
// many beyond the planner (not the command queue's places: a host that
// reads answers late released them all on a stale word, and `pause now`
// at 2 x measured 3.214 mm once). A printer that answers probes at once
// for another reason (a delta: Marlin returns before the planner) would
// seem always to have room: the one move let go on each probe's word waits
// for a block; a few such waits (while no probe ever did) stop the probes,
// and the speed learnt on their word is forgotten. Probes that come late
// as the model said space the next ones (probe_spacing.hpp): at the file's
// pace a probe went with every held move; the model's own wake lets the
// moves go between them, and the floor is not forgotten meanwhile. A probe
// that waited also says when the moves behind its block began (not before
// it arrived): the floor's closest measure of a printer faster than the
// file, so that the model keeps up with it and its probes confirm it.
#include <algorithm>
#include <array>
#include <cstddef>

#include "gcode/serial/protocol/pace_rate.hpp"
#include "gcode/serial/protocol/probe_credit.hpp"
#include "gcode/serial/protocol/probe_spacing.hpp"

namespace gcode::serial {

class Pacer {
 public:
  static constexpr double kNever = 1e300;
  static constexpr double kUnknown = 1e300;     // a move's arrival, not known
  static constexpr std::size_t kMaxBlocks = 64;
  static constexpr double kGrace = 0.25;        // of a block: how late an answer is before it waited
  static constexpr long long kMinShown = 8;     // moves a span of the printer's shown speed holds at least
  // Of the shown speed: the simulated clock's own slack (from 1 x to 10 x
  // the best span came to at most 1.0002 of the printer's speed). Each %
  // less leaves the model that much slower than a printer at 1.25 x or 2 x,
  // and its probes find the room that leaves (probe_spacing.hpp).
  static constexpr double kShownMargin = 0.99;
  static constexpr double kFloorDecay = 0.995;  // per answered move: the shown speed is forgotten slowly
  static constexpr double kOutpaced = 0.5;      // of the moves' time at the model's pace: a probe's round trip that long may be the limit
  static constexpr double kQuick = 0.5;         // of a block at the model's pace: a probe answered within it found room at once
  static constexpr double kStall = 4;           // blocks at the file's pace: a move's answer later than that is the host's stall
  static constexpr int kCreditInFlight = 2;     // a move goes on probes' word only while fewer are unanswered
  static constexpr int kFoundOut = 4;           // moves that waited while probes never did: probes are answered at once

  // A move `number` may go, with `moves_in_flight` sent and not answered
  // and a planner of `planner_blocks`? When it must wait and nothing is in
  // flight (no answer will come), wake() says when it may go.
  bool blocked(double now, int moves_in_flight, long long number, int planner_blocks);

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

  // A move of no length now, with the moves in flight? (Only without
  // ADVANCED_OK, once the planner was filled, and while its answers may
  // still be believed.)
  bool probe_wanted(int planner_blocks) const;
  // One now, ahead of the last moves a probe let go, so that its answer
  // comes before they have gone (probe_credit.hpp)?
  bool probe_ahead(int planner_blocks) const;
  // Its answer: `now`, and when its last byte reached the printer.
  void probe_answered(double now, double arrival, int planner_blocks);

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
    double not_before;  // it started no earlier: handed to the port, or a probe waited for the block ahead (kNever: not known)
  };
  struct Released {
    long long number = -1;
    double at = 0;
  };
  std::size_t blocks(int planner_blocks) const;
  // Move `index` (a count of answered moves), kept while newer than oldest().
  Planned& move(long long index) { return ring_[static_cast<std::size_t>(index) % kHistory]; }
  const Planned& move(long long index) const { return ring_[static_cast<std::size_t>(index) % kHistory]; }
  long long oldest() const { return std::max(answered_ - static_cast<long long>(kHistory) + 1, 1LL); }
  const Planned* next_to_end(double now, int planner_blocks) const;
  bool waited_for_block(double late, bool bounded, long long block) const;
  bool confirms_model(double said, double arrival, double entered, double late, long long freed) const;
  bool outpaced_by_probes(double now);
  void heard_wait(double late, bool bounded, long long freed, bool probes_move);
  bool observe(long long freed, double entered, double late, bool bounded, bool probe);
  // An answer's timing: when its command entered the planner, how late it
  // came past the host's own latency, and whether it came apart from the
  // answer before it.
  struct Timing {
    double entered;
    double late;
    bool apart;
  };
  Timing timing(double now, double arrival);
  void sight(long long index, double t);
  double end_with(long long from, double start, long long to, double factor) const;
  void chain();
  void learn_floor(long long freed, double now);
  bool release(long long number, double now);
  double shown(long long freed, double now) const;

  std::array<Planned, kHistory> ring_{};
  long long answered_ = 0;      // moves answered; the newest is move(answered_)
  long long known_ = 0;         // moves up to this one are known to have ended,
  double anchor_ = -kNever;     // the last of them then
  long long sighted_ = -1;      // the move whose end was last sighted,
  double sighted_at_ = 0;       // then

  double base_ = kNever;         // the least answer minus arrival: the host's own latency
  double move_base_ = kNever;     // the least answer minus arrival of a move
  double jitter_ = 0;           // how late answers that did not wait came, on average
  bool clean_ = true;           // nothing but moves (or instant commands) since the last move
  double last_now_ = -kNever;   // when the last move was answered
  std::array<Released, kHistory> released_{};  // by line number
  double floor_ = PaceRate::kMin;  // the speed the printer has shown lately
  bool advanced_ = false;        // ADVANCED_OK's P seen: no probes
  long long probes_ = 0;        // probe answers,
  long long late_probes_ = 0;   // those that waited for a block
  bool link_bound_ = false;     // probes showed the link is the limit, and none since that the planner was full
  double last_probe_ = -kNever; // when the last probe was answered,
  long long probe_mark_ = 0;    // the moves answered then
  bool probes_unheard_ = false; // moves waited for a block while no probe had: probes are answered at once
  int unheard_waits_ = 0;       // such waits so far
  ProbeCredit credit_;          // moves let go beyond the model on probes' word
  ProbeSpacing spacing_;        // moves between probes that found the model right
  bool probe_credit_ = false;   // a probe found room: the next move released is its
  long long probe_move_ = -1;   // that move, until answered
  double wake_ = kNever;
  PaceRate rate_;
};

}  // namespace gcode::serial
