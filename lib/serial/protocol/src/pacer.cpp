#include "gcode/serial/protocol/pacer.hpp"

#include <algorithm>
#include <cmath>

namespace gcode::serial {

std::size_t Pacer::blocks(int planner_blocks) const {
  return std::min(kMaxBlocks, static_cast<std::size_t>(std::max(1, planner_blocks)));
}

int Pacer::ahead(double now, int planner_blocks) const {
  const long long from = std::max({known_ + 1, oldest(), answered_ - static_cast<long long>(blocks(planner_blocks)) + 1});
  int ahead = 0;
  for (long long i = from; i <= answered_; ++i) ahead += move(i).end > now ? 1 : 0;
  return ahead;
}

const Pacer::Planned* Pacer::next_to_end(double now, int planner_blocks) const {
  const long long from = std::max({known_ + 1, oldest(), answered_ - static_cast<long long>(blocks(planner_blocks)) + 1});
  const Planned* first = nullptr;
  for (long long i = from; i <= answered_; ++i)
    if (move(i).end > now && (first == nullptr || move(i).end < first->end)) first = &move(i);
  return first;
}

bool Pacer::blocked(double now, int moves_in_flight, long long number, int planner_blocks) {
  const int n = static_cast<int>(blocks(planner_blocks));
  const int held = moves_in_flight + ahead(now, planner_blocks);
  wake_ = kNever;
  // Beyond the model only on probes' word that the planner had room.
  if (held < n || (moves_in_flight < kCreditInFlight && credit_.take())) return release(number, now);
  const Planned* first = next_to_end(now, planner_blocks);
  const double next = first != nullptr ? first->end : kNever;
  // With nothing in flight no answer will come: wake when a block ends.
  if (moves_in_flight == 0) wake_ = next;
  return true;
}

// The end of move `to` if the moves from `from` on ran at `factor`, the
// first starting at `start` at the earliest, each when it was answered
// and the one before had ended.
double Pacer::end_with(long long from, double start, long long to, double factor) const {
  double end = start;
  for (long long i = from; i <= to; ++i) end = std::max(end, move(i).entered) + move(i).seconds / factor;
  return end;
}

void Pacer::sight(long long index, double t) {
  if (sighted_ > 0 && index - sighted_ < PaceRate::kMinSpan) return;  // too close to measure: the older one stays
  if (sighted_ > 0 && sighted_ + 1 >= oldest()) {
    // The factor that makes the moves since the last sighting end now.
    double lo = PaceRate::kMin;
    double hi = PaceRate::kMax;
    if (end_with(sighted_ + 1, sighted_at_, index, hi) < t) {
      for (int k = 0; k < 40; ++k) {
        double mid = std::sqrt(lo * hi);
        (end_with(sighted_ + 1, sighted_at_, index, mid) > t ? lo : hi) = mid;
      }
      rate_.sample(std::sqrt(lo * hi), static_cast<double>(index - sighted_));
    }
  }
  sighted_ = index;
  sighted_at_ = t;
}

// An answer `late` past the host's own latency by more than that wanders
// (and more than a part of the block it may have waited for) waited.
bool Pacer::waited_for_block(double late, bool bounded, long long block) const {
  return bounded && late > std::max(kGrace * move(block).seconds / rate_.factor(), 3 * jitter_);
}

// The move just answered took the block of move `freed`: that one had ended
// by `entered`, or ended then if the answer was late (it waited for it).
bool Pacer::observe(long long freed, double entered, double late, bool bounded, bool probe) {
  if (freed <= known_ || freed < oldest()) return false;
  if (waited_for_block(late, bounded, freed)) {
    // The answer came that late after the block ended, less the host's
    // usual latency (a model later than the printer starves it). Not a
    // probe's: how late probes come is partly their waits for blocks
    // shorter than the model said, and the moves the model lets go alone
    // between spaced probes (probe_spacing.hpp) would overfill by one.
    known_ = freed;
    anchor_ = entered - (probe ? 0 : jitter_);
    sight(freed, anchor_);
    return true;
  }
  // It had ended by then at the latest. (How late such answers come is
  // how much the host's latency wanders.)
  if (bounded) jitter_ += (std::max(0.0, late) - jitter_) / 16;
  known_ = freed;
  anchor_ = bounded ? std::min(move(freed).end, entered) : move(freed).end;
  return false;
}

void Pacer::chain() {
  const double factor = rate_.factor();
  double prev = anchor_;
  for (long long i = known_ + 1; i <= answered_; ++i) {
    Planned& p = move(i);
    p.end = std::max(prev, p.entered) + p.seconds / factor;
    prev = p.end;
  }
}

Pacer::Timing Pacer::timing(double now, double arrival) {
  const bool known = arrival != kUnknown;
  // The least answer time seen is the host's own latency: a planner that
  // is always full makes every answer wait, so no recent window would do.
  if (known) base_ = std::min(base_, now - arrival);
  const double base = base_ < kNever ? base_ : 0;
  Timing t;
  // When it entered the planner: its answer, less the way back.
  t.entered = now - std::max(0.0, base);
  t.late = known ? now - arrival - base : 0;
  // An answer read together with the one before it (no time between them)
  // was late because the host was: a stall, not a wait for a block.
  t.apart = now - last_now_ >= 0.5 * t.late;
  return t;
}

void Pacer::answered(const Answer& a, int planner_blocks, double time_scale) {
  const auto n = static_cast<long long>(blocks(planner_blocks));
  const bool known = a.arrival != kUnknown;
  const Timing t = timing(a.now, a.arrival);
  const double entered = t.entered;
  if (known_ < answered_ + 1 - static_cast<long long>(kHistory)) {
    // The oldest move kept makes room: the model takes its end as known.
    known_ = answered_ + 1 - static_cast<long long>(kHistory);
    anchor_ = std::max(anchor_, move(known_).end);
  }
  ++answered_;
  const Released& r = released_[static_cast<std::size_t>(a.number) % kHistory];
  move(answered_) = {entered, a.nominal / (time_scale > 0 ? time_scale : 1), kNever,
                     r.number == a.number ? r.at : kNever};
  const long long freed = answered_ - n;  // the move whose block this one took
  advanced_ = advanced_ || a.planner_free >= 0;
  if (a.planner_free >= 0 && clean_) {
    // ADVANCED_OK: the planner holds its size less P moves, this one among
    // them; the one before the oldest of them ended by now (within a block).
    const long long holds = std::clamp(n - a.planner_free, 1LL, n);
    known_ = std::max(known_, answered_ - holds);
    anchor_ = entered;
    sight(answered_ - holds, entered);
  } else {
    const bool bounded = clean_ && known && t.apart;
    observe(answered_ - n, entered, t.late, bounded, false);
    // Late past the least time a move took to be answered: a move's line
    // takes the printer longer to read than a probe's, which may have set
    // the base.
    if (known) move_base_ = std::min(move_base_, a.now - a.arrival);
    heard_wait(known ? a.now - a.arrival - move_base_ : 0, bounded, answered_ - n, a.number == probe_move_);
  }
  if (a.number >= probe_move_) probe_move_ = -1;
  chain();
  // (Not while probes are spaced: the model holds, and the floor their
  // answers refresh would sink below the printer's pace between them.)
  if (spacing_.gap() == 0) floor_ *= kFloorDecay;
  learn_floor(freed, a.now);
  clean_ = true;
  last_now_ = a.now;
}

// A move that clearly waited for a block (later than the host's latency
// wanders, and by a part of the block it waited for at the file's speed:
// at 10 x a block is shorter than that wandering, and the timing rule of
// observe() takes noise for waits) says the planner was full: no more moves
// beyond the model. (Those let go on probes' word are not in its count.)
void Pacer::heard_wait(double late, bool bounded, long long freed, bool probes_move) {
  const double noise = std::max(3 * jitter_, 2 * move_base_);
  const double block = move(std::max(freed, oldest())).seconds;
  // Far longer than the block at the file's pace it would have waited for
  // (with room for acceleration) is a stall of the host's, not a wait.
  if (!bounded || late <= std::max(kGrace * block, noise) || late > kStall * block) return;
  // The one move let go on a probe's word waited, and no probe ever did:
  // the printer answers probes at once, and their word that it had room
  // is worth nothing. (A delta's waits after most of its probes; the
  // host's own stalls, now and then, are not taken for it.)
  if (probes_move && late_probes_ == 0 && ++unheard_waits_ >= kFoundOut && 3 * unheard_waits_ >= 2 * probes_ &&
      !probes_unheard_) {
    // The speed their answers showed is forgotten: back to the file's.
    probes_unheard_ = true;
    floor_ = PaceRate::kMin;
    rate_ = PaceRate{};
    chain();
  }
  credit_.full();
}

void Pacer::learn_floor(long long freed, double now) {
  floor_ = std::max(shown(freed, now), floor_);
  if (rate_.factor() < floor_) {
    rate_.at_least(floor_);
    chain();
  }
}

bool Pacer::probe_wanted(int planner_blocks) const {
  // Right behind the moves the last probe let go: its answer says whether
  // the planner still had room once they were in (probe_credit.hpp).
  return !advanced_ && !probes_unheard_ && credit_.due() && probe_move_ < 0 && !probe_credit_ &&
         answered_ >= static_cast<long long>(blocks(planner_blocks)) && spacing_.due(answered_);
}

bool Pacer::probe_ahead(int planner_blocks) const { return credit_.left() > 0 && probe_wanted(planner_blocks); }

// The probe went after every move answered so far and took no block: its
// answer came once the oldest of the last n of them had left the planner.
void Pacer::probe_answered(double now, double arrival, int planner_blocks) {
  ++probes_;
  // (Also after moves the model let go alone between spaced probes: at ten
  // times the file's pace the link is the limit, and a probe that finds the
  // printer took them faster than the link brought them says so.)
  const bool outpaced = outpaced_by_probes(now);
  // A move let go on an earlier one's word waited for a block: this one's
  // answer at once says nothing of room.
  if (probes_unheard_) return;
  const long long freed = answered_ - static_cast<long long>(blocks(planner_blocks)) + 1;
  // After a command that waits its lateness is not the planner's.
  if (!clean_ || arrival == kUnknown || freed < oldest() || freed <= known_) {
    credit_.answered(false, false, planner_blocks);
    return;
  }
  const Timing t = timing(now, arrival);
  const double said = move(freed).end;  // the model's, before the answer corrects it
  const bool waited = observe(freed, t.entered, t.late, t.apart, true);
  if (waited) {
    ++late_probes_;
    // It waited for block `freed`, which so ended after it arrived: the
    // move behind began no earlier. From its release instead, the floor
    // counted the time it sat in a full planner (a planner's worth of
    // blocks), stayed at 1.75-1.94 for a printer twice as fast, and the
    // model, that much slower, left the room its probes kept finding.
    Planned& next = move(freed + 1);
    next.not_before = next.not_before < kNever ? std::max(next.not_before, arrival) : arrival;
  }
  // More moves only on a probe that came within half a block at the
  // model's pace: one a block late is a planner that is full, whatever
  // the host's latency let observe() take it for.
  const bool quick = t.late < kQuick * move(freed).seconds / rate_.factor();
  // Once shown, the link stays the limit until a probe says the planner
  // was full: the model's pace, which the link held down, is no measure of
  // slower moves (a layer's first ones after its fast infill).
  link_bound_ = !waited && quick && (link_bound_ || outpaced);
  const int c = credit_.answered(!waited, link_bound_, planner_blocks);
  spacing_.answered(waited || confirms_model(said, arrival, t.entered, t.late, freed), answered_);
  // Room, and only the model's one block for it: the next probe waits for
  // that move's answer, so a printer that answers probes at once is found
  // out by its wait before another goes.
  probe_credit_ = !waited && c == 0;
  chain();
  learn_floor(freed, now);
}

// Did a probe that found block `freed` free `late` past its arrival come
// as the model said (it `said` the block ends then)? Late by a part of a
// block: the planner was full. Or, when the model said the block ended
// after the probe arrived, answered no sooner than a part of a block
// before that: at 2 x a move's and the probe's lines take half a block on
// the wire, so a probe sent as the model filled the planner arrived with
// little of that block left, and, answered as the model said, seemed to
// find room (1596 probes for 5983 lines; a probe per held move again).
// When the model says the block ended before the probe arrived (at 10 x,
// the link the limit), its answer tells nothing of the model's pace.
bool Pacer::confirms_model(double said, double arrival, double entered, double late, long long freed) const {
  const double grace = kGrace * move(freed).seconds / rate_.factor();
  return late > grace || (said > arrival && said - entered < grace);
}

// Did the moves answered since the last probe's answer run, at the model's
// pace, in less than twice the time since (kOutpaced)? Then a move per
// probe's round trip may feed the planner slower than it drains, and more
// per probe are wanted. Not while the round trip is short against the
// moves: with none (a host that answers itself at once), a move per probe
// keeps up with any printer, and more would only overfill it.
bool Pacer::outpaced_by_probes(double now) {
  double work = 0;
  for (long long i = std::max(probe_mark_ + 1, oldest()); i <= answered_; ++i) work += move(i).seconds;
  const bool outpaced = last_probe_ > -kNever && now - last_probe_ > kOutpaced * work / rate_.factor();
  last_probe_ = now;
  probe_mark_ = answered_;
  return outpaced;
}

bool Pacer::release(long long number, double now) {
  released_[static_cast<std::size_t>(number) % kHistory] = {number, now};
  if (probe_credit_) probe_move_ = number;
  probe_credit_ = false;
  return false;
}

// What the printer has shown it does at least: move `freed` had ended when
// the move just answered found a block (`now`), and no move starts before
// it was handed to the port, nor before a probe that waited for the block
// ahead of it arrived. So the moves from any one kept up to `freed` ran, at
// the file's feed rates, within the time from that one's start at the
// earliest to `now`: a speed the printer reached whatever the host's
// latency did to the answers' times (late answers, late releases only
// lower it), the best of
// those spans a floor for the factor that never stands above the printer's
// real pace, as a factor learnt from timing can. (It takes a planner of the
// size assumed; one that holds more would let moves on unseen.)
double Pacer::shown(long long freed, double now) const {
  double seconds = 0, best = 0;
  for (long long i = freed; i >= oldest() && freed - i < static_cast<long long>(kHistory); --i) {
    seconds += move(i).seconds;
    const double took = now - move(i).not_before;
    if (freed - i + 1 >= kMinShown && move(i).not_before < kNever && took > 0) best = std::max(best, seconds / took);
  }
  return best * kShownMargin;
}

void Pacer::answered_other(bool waits) {
  if (waits) interrupted();
}

void Pacer::interrupted() {
  // The time up to the next sighting is not the moves' alone.
  clean_ = false;
  sighted_ = -1;
  spacing_.reset();
}

}  // namespace gcode::serial
