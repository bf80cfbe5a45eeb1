// The sender's pacer (serial/pacer.hpp) and its speed factor
// (serial/pace_rate.hpp): no more moves ahead of the nozzle than the planner
// holds, and the printer's real pace learnt from what it has shown, never
// above it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <deque>
#include <utility>

#include "gcode/serial/protocol/pace_rate.hpp"
#include "gcode/serial/protocol/pacer.hpp"
#include "gcode/serial/protocol/probe_credit.hpp"

using namespace gcode::serial;

namespace {

// A planner of `blocks` blocks that runs moves `factor` times faster than
// their nominal time and answers a move when it gets a block; the host
// sends whenever the pacer lets it, with no latency. What the printer did
// is counted: the time its planner stood empty, the most moves ever ahead
// of the nozzle.
struct Scripted {
  int blocks = 4;
  double factor = 1;
  double now = 0;
  std::deque<double> ends;   // the planner's blocks, when each ends
  double starved = 0;
  std::size_t most_ahead = 0;
  long long number = 0;
  Pacer pacer;
  bool advanced_ok = false;
  double latency = 0;        // how late the host reads an answer, at most
  unsigned seed = 1;
  // The host asks with a move of no length whenever the pacer wants one;
  // the printer holds it until a block is free (Marlin) or answers it at
  // once (a delta).
  bool probes = false;
  bool holds_probes = true;
  int probes_sent = 0;

  double late() {
    seed = seed * 1103515245u + 12345u;
    return latency * static_cast<double>((seed >> 16) % 1000) / 1000.0;
  }
  void drain() {
    while (!ends.empty() && ends.front() <= now) ends.pop_front();
  }
  void probe() {
    ++probes_sent;
    drain();
    double answered = now;
    if (holds_probes && static_cast<int>(ends.size()) >= blocks) answered = ends.front();
    const double arrival = now;
    now = answered + late();
    pacer.probe_answered(now, arrival, blocks);
  }

  // One move of `seconds` nominal: sent as soon as the pacer lets it,
  // answered when it has a block.
  void move(double seconds) {
    while (pacer.blocked(now, 0, number + 1, blocks)) {
      if (probes && pacer.probe_wanted(blocks)) {
        probe();
        continue;
      }
      REQUIRE(pacer.wake() < Pacer::kNever);
      now = std::max(now, pacer.wake());
    }
    ++number;
    drain();
    double entered = now;
    most_ahead = std::max(most_ahead, ends.size() + 1);
    if (static_cast<int>(ends.size()) >= blocks) {
      entered = ends.front();
      ends.pop_front();
    }
    double start = ends.empty() ? entered : std::max(ends.back(), entered);
    if (ends.empty() && number > 1 && last_end < entered) starved += entered - last_end;
    ends.push_back(start + seconds / factor);
    last_end = ends.back();
    Pacer::Answer a;
    a.number = number;
    a.nominal = seconds;
    // The host reads the answer up to `latency` seconds late (a fixed,
    // uneven sequence).
    const double late_by = late();
    a.now = entered + late_by;
    a.arrival = now;
    a.planner_free = advanced_ok ? blocks - static_cast<int>(ends.size()) : -1;
    now = entered + late_by;
    pacer.answered(a, blocks, 1);
  }
  double last_end = 0;
};

// Marlin's 16 blocks at `factor` x, the host asking with moves of no length.
Scripted probing(double factor) {
  Scripted s;
  s.blocks = 16;
  s.factor = factor;
  s.probes = true;
  return s;
}

// A printer behind a serial link, the host pacing with moves of no length
// as gc-send does: each line takes `link` seconds on the wire, one after
// the other (a probe a tenth of that); the host keeps at most `queue` lines in flight (Marlin's
// BUFSIZE); the printer takes each line in order once it has arrived and,
// a move, once a block is free (a probe too, unless it answers probes at
// once); each answer reaches the host `back` seconds later. Moves run
// `factor` times faster than their nominal time, or take none (`instant`).
// Counted: the time the planner stood empty, the most moves ahead of the
// nozzle (in the planner or on their way to it), the time it all took.
struct Linked {
  int blocks = 16;
  int queue = 4;
  double factor = 1;
  bool instant = false;
  double link = 0.25;
  double back = 0.02;
  bool pace = true;
  bool holds_probes = true;
  Pacer pacer;
  double now = 0;
  double starved = 0;
  std::size_t most_ahead = 0;
  int probes_sent = 0;
  long long number = 0;

  struct Line {
    long long number;  // 0: a probe
    double seconds;
    double arrival;
    double answer;
  };
  std::deque<Line> flight;
  double wire_free = 0;         // when the wire is free for the next line
  double taken = 0;             // when the printer took the last line
  std::deque<double> planner;   // when the moves in it end
  std::deque<double> ahead;     // when the moves sent and not ended end
  double last_end = 0;

  // The printer takes a line that arrived at `arrival`: when it answers.
  double take(bool move, double seconds, double arrival) {
    double t = std::max(arrival, taken);
    while (!planner.empty() && planner.front() <= t) planner.pop_front();
    if ((move || holds_probes) && static_cast<int>(planner.size()) >= blocks) {
      t = planner.front();
      planner.pop_front();
    }
    taken = t;
    if (move) {
      if (planner.empty() && number > 1 && last_end < t) starved += t - last_end;
      const double end = (planner.empty() ? t : std::max(planner.back(), t)) + (instant ? 0 : seconds / factor);
      planner.push_back(end);
      ahead.push_back(end);
      last_end = end;
    }
    return t + back;
  }
  void send(bool move, double seconds) {
    // A probe's "G1" is 3 bytes, a move's line some 30.
    const double arrival = std::max(now, wire_free) + (move ? link : link / 10);
    wire_free = arrival;
    if (move) ++number;
    while (!ahead.empty() && ahead.front() <= now) ahead.pop_front();
    flight.push_back({move ? number : 0, seconds, arrival, take(move, seconds, arrival)});
    most_ahead = std::max(most_ahead, ahead.size());
  }
  void answer(const Line& l) {
    if (l.number == 0) {
      pacer.probe_answered(now, l.arrival, blocks);
      return;
    }
    pacer.answered({l.number, l.seconds, now, l.arrival, -1}, blocks, 1);
  }
  // The host's loop: `moves` moves of `seconds` nominal each.
  void run(int moves, double seconds) {
    int sent = 0;
    while (sent < moves || !flight.empty()) {
      while (!flight.empty() && flight.front().answer <= now) {
        const Line l = flight.front();
        flight.pop_front();
        answer(l);
      }
      pacer.clear_wake();
      while (sent < moves && static_cast<int>(flight.size()) < queue) {
        int in_flight = 0;
        bool probing = false;
        for (const Line& l : flight) {
          in_flight += l.number > 0 ? 1 : 0;
          probing = probing || l.number == 0;
        }
        if (pace && pacer.blocked(now, in_flight, number + 1, blocks)) {
          if (!probing && pacer.probe_wanted(blocks)) {
            ++probes_sent;
            send(false, 0);
          }
          break;
        }
        send(true, seconds);
        ++sent;
        // (gc-send's fill: a probe ahead of the last moves let go.)
        if (pace && !probing && pacer.probe_ahead(blocks)) {
          ++probes_sent;
          send(false, 0);
        }
      }
      double next = flight.empty() ? Pacer::kNever : flight.front().answer;
      next = std::min(next, pacer.wake());
      if (sent == moves && flight.empty()) break;
      REQUIRE(next < Pacer::kNever);
      now = std::max(now, next);
    }
  }
};

// The same moves paced and with no pacing: how long each took, how long
// its planner stood empty.
struct AgainstUnpaced {
  double paced_time, unpaced_time, paced_starved, unpaced_starved;
  std::size_t paced_ahead;
};
AgainstUnpaced against_unpaced(Linked printer, int moves) {
  Linked unpaced = printer;
  unpaced.pace = false;
  printer.run(moves, 1);
  unpaced.run(moves, 1);
  return {printer.now, unpaced.now, printer.starved, unpaced.starved, printer.most_ahead};
}

}  // namespace

TEST_CASE("pacer: moves in flight and answered moves still running fill the planner", "[serial][pacer]") {
  Pacer p;
  CHECK_FALSE(p.blocked(0, 3, 1, 4));
  CHECK(p.blocked(0, 4, 1, 4));
  CHECK(p.wake() == Pacer::kNever);  // an answer will come
  // Two answered moves of 1 s each run one after the other: until 1 and 2.
  p.answered({1, 1, 0, 0, -1}, 4, 1);
  p.answered({2, 1, 0, 0, -1}, 4, 1);
  CHECK(p.ahead(0.5, 4) == 2);
  CHECK(p.blocked(0.5, 2, 3, 4));
  CHECK_FALSE(p.blocked(1.5, 2, 3, 4));  // the first has ended
  CHECK_FALSE(p.blocked(2.5, 3, 3, 4));
  // A simulated printer's time scale shortens the moves: 10 printer seconds at 20 x.
  p.answered({3, 10, 5, 5, -1}, 4, 20);
  CHECK(p.ahead(5.4, 4) == 1);
  CHECK(p.ahead(5.6, 4) == 0);
}

TEST_CASE("pacer: with nothing in flight it wakes when a block ends", "[serial][pacer]") {
  Pacer p;
  for (int i = 1; i <= 4; ++i) p.answered({i, 2, 0, 0, -1}, 4, 1);  // end at 2, 4, 6, 8
  CHECK(p.blocked(1, 0, 5, 4));
  CHECK(p.wake() == 2);
  p.clear_wake();
  CHECK(p.wake() == Pacer::kNever);
}

TEST_CASE("pacer: with ADVANCED_OK a printer twice as fast as the file is learnt and never starved", "[serial][pacer]") {
  Scripted s;
  s.factor = 2;
  s.advanced_ok = true;
  for (int i = 0; i < 100; ++i) s.move(1);
  CHECK(s.pacer.speed_factor() == Approx(2).epsilon(0.1));
  double before = s.starved;
  double t0 = s.now;
  for (int i = 0; i < 200; ++i) s.move(1);
  INFO("starved " << s.starved - before << " s of " << s.now - t0);
  CHECK(s.starved - before < 0.02 * (s.now - t0));
  // Never above the printer's pace, never more ahead of the nozzle than the planner holds.
  CHECK(s.pacer.speed_factor() <= 2.0 + 1e-9);
  CHECK(s.most_ahead <= static_cast<std::size_t>(s.blocks));
}

TEST_CASE("pacer: with ADVANCED_OK a printer that slows down and speeds up again is followed", "[serial][pacer]") {
  Scripted s;
  s.factor = 2;
  s.advanced_ok = true;
  for (int i = 0; i < 100; ++i) s.move(1);
  s.factor = 1;  // the speed knob back to 100 %
  for (int i = 0; i < 300; ++i) s.move(1);
  CHECK(s.pacer.speed_factor() == Approx(1).epsilon(0.1));
  // And faster again (moves of another length: the factor is per second of motion).
  s.factor = 1.25;
  double before = s.starved;
  double t0 = s.now;
  for (int i = 0; i < 300; ++i) s.move(0.5);
  CHECK(s.pacer.speed_factor() > 1.1);
  CHECK(s.pacer.speed_factor() <= 1.25 + 1e-9);
  CHECK(s.starved - before < 0.05 * (s.now - t0));
}

TEST_CASE("pacer: without ADVANCED_OK the planner is never overfilled to find a faster printer", "[serial][pacer]") {
  // A move more than the planner holds is a piece more ahead of the nozzle
  // at a pause; answers that come as soon as a move arrives say nothing of
  // the planner's pace.
  Scripted s;
  s.blocks = 16;
  s.factor = 2;
  for (int i = 0; i < 500; ++i) s.move(1);
  CHECK(s.most_ahead <= static_cast<std::size_t>(s.blocks));
  CHECK(s.pacer.speed_factor() >= 1);
  CHECK(s.pacer.speed_factor() <= 2.0 + 1e-9);
}

TEST_CASE("pace rate: samples only lower the factor, in proportion to the moves they span, and the floor raises it", "[serial][pacer]") {
  PaceRate r;
  CHECK(r.factor() == 1);
  r.sample(2, PaceRate::kSpan);  // timing alone never raises it
  CHECK(r.factor() == 1);
  r.at_least(2);  // a speed the printer has shown raises it at once
  CHECK(r.factor() == Approx(2));
  r.at_least(1.2);  // and a lower one does not lower it
  CHECK(r.factor() == Approx(2));
  r.sample(1.5, PaceRate::kSpan / 2);  // half a window: half the way down (geometrically)
  CHECK(r.factor() == Approx(std::sqrt(2 * 1.5)));
  r.sample(0.5, PaceRate::kSpan);  // never slower than the file's feed rates
  CHECK(r.factor() == PaceRate::kMin);
  r.at_least(1000);
  CHECK(r.factor() == PaceRate::kMax);
}

TEST_CASE("pacer: answers the host reads late never make a printer at the file's speed look faster", "[serial][pacer]") {
  // At 1x a factor learnt too high holds more moves in flight than the
  // planner takes (gc-send's pause now stopped 3.5 mm on, not 3.2).
  for (bool advanced : {false, true}) {
    INFO("ADVANCED_OK " << advanced);
    Scripted s;
    s.blocks = 16;
    s.advanced_ok = advanced;
    s.latency = 3;  // up to three blocks late, as a loaded host reads them
    for (int i = 0; i < 1000; ++i) s.move(1);
    CHECK(s.pacer.speed_factor() <= 1.0 + 1e-9);
    CHECK(s.most_ahead <= static_cast<std::size_t>(s.blocks));
  }
}

TEST_CASE("pacer: without ADVANCED_OK moves of no length find a faster printer's pace without overfilling it", "[serial][pacer]") {
  // Marlin holds a bare G1 until a block is free and then drops it: its
  // answer says the planner had room, or, late, that a block just ended.
  for (double factor : {1.25, 2.0, 10.0}) {
    INFO("printer at " << factor << " x");
    Scripted s = probing(factor);
    for (int i = 0; i < 200; ++i) s.move(1);
    const double before = s.starved;
    const double t0 = s.now;
    for (int i = 0; i < 500; ++i) s.move(1);
    INFO("starved " << s.starved - before << " s of " << s.now - t0 << ", " << s.probes_sent << " probes");
    CHECK(s.starved - before < 0.01 * (s.now - t0));
    CHECK(s.most_ahead <= static_cast<std::size_t>(s.blocks));
    CHECK(s.pacer.speed_factor() <= factor + 1e-9);
  }
}

TEST_CASE("pacer: moves of no length at the file's pace never put a move more ahead of the nozzle", "[serial][pacer]") {
  for (double latency : {0.0, 3.0}) {
    INFO("host latency up to " << latency << " blocks");
    Scripted s = probing(1);
    s.latency = latency;
    for (int i = 0; i < 1000; ++i) s.move(1);
    CHECK(s.probes_sent > 0);
    CHECK(s.most_ahead <= static_cast<std::size_t>(s.blocks));
    CHECK(s.pacer.speed_factor() <= 1.0 + 1e-9);
  }
}

TEST_CASE("pacer: a printer that answers moves of no length at once is found out by the one move released on its word", "[serial][pacer]") {
  // A delta (Marlin returns before the planner for a move of no length):
  // its answers always say there is room. The one move released on the
  // first of them waits for a block; then no more probes go.
  Scripted s = probing(1);
  s.holds_probes = false;
  for (int i = 0; i < 100; ++i) s.move(1);
  const int sent = s.probes_sent;
  CHECK(sent >= 1);
  CHECK(s.most_ahead <= static_cast<std::size_t>(s.blocks) + 1);
  s.most_ahead = 0;
  for (int i = 0; i < 500; ++i) s.move(1);
  CHECK(s.probes_sent == sent);
  CHECK(s.most_ahead <= static_cast<std::size_t>(s.blocks));
  CHECK(s.pacer.speed_factor() <= 1.0 + 1e-9);
}

TEST_CASE("pacer: with ADVANCED_OK no move of no length is wanted", "[serial][pacer]") {
  Scripted s = probing(2);
  s.advanced_ok = true;
  for (int i = 0; i < 200; ++i) s.move(1);
  CHECK(s.probes_sent == 0);
}

TEST_CASE("pacer: a printer that drains its planner faster than the link fills it is fed at the link's speed", "[serial][pacer]") {
  // 10 x: a move takes a third of the time its line takes on the wire.
  // Probes that keep finding room let more moves go each time (1, 2, 4
  // ... 16); one probe answer per move held it to a probe's round trip per
  // move (gc-send at 10 x: 117 commands/s against 405 with --no-pace).
  Linked s;
  s.factor = 10;
  AgainstUnpaced r = against_unpaced(s, 2000);
  INFO("paced " << r.paced_time << " s, starved " << r.paced_starved << "; unpaced " << r.unpaced_time
                << " s, starved " << r.unpaced_starved);
  CHECK(r.paced_time <= 1.05 * r.unpaced_time);
  CHECK(r.paced_starved <= r.unpaced_starved + 0.01 * r.unpaced_time);
}

TEST_CASE("pacer: a printer whose moves take no time is fed at the link's speed", "[serial][pacer]") {
  // OctoPrint's virtual printer, Klipper's pseudo-tty, gc-virtual-printer
  // --instant-moves: every answer comes at once.
  Linked s;
  s.instant = true;
  AgainstUnpaced r = against_unpaced(s, 2000);
  INFO("paced " << r.paced_time << " s, unpaced " << r.unpaced_time << " s");
  CHECK(r.paced_time <= 1.05 * r.unpaced_time);
}

TEST_CASE("pacer: behind a link, a printer at the file's pace or a little faster is followed and never overfilled", "[serial][pacer]") {
  // At the file's pace its probes come late, or soon after a move that
  // takes longer than their round trip: one move goes per block that ends.
  // Faster, probes that find room may let more go (probe_credit.hpp), but
  // only while fewer than two moves are unanswered (Pacer::kCreditInFlight):
  // a bet that lost holds no more than those beyond the planner, whatever
  // the command queue would take (4 places, or 8), and the link still runs
  // full at 10 x. (gc-send's pause now at 2 x stays within the planner's
  // 16 blocks and these 2 on the virtual printer.)
  for (int queue : {4, 8}) {
    for (double factor : {1.0, 1.25, 2.0, 10.0}) {
      INFO("printer at " << factor << " x, a queue of " << queue);
      Linked s;
      s.factor = factor;
      s.queue = queue;
      AgainstUnpaced r = against_unpaced(s, 1000);
      INFO("paced " << r.paced_time << " s, starved " << r.paced_starved << "; unpaced " << r.unpaced_time
                    << " s, starved " << r.unpaced_starved);
      CHECK(r.paced_ahead <= static_cast<std::size_t>(s.blocks + (factor > 1 ? 2 : 0)));
      CHECK(r.paced_time <= 1.05 * r.unpaced_time);
      // (At 10 x the planner starves either way; its test above, on 2000
      // moves, holds paced within 1 % of unpaced.)
      if (factor < 10) CHECK(r.paced_starved <= r.unpaced_starved + 0.01 * r.unpaced_time);
    }
  }
}

TEST_CASE("pacer: behind a link, a printer that answers moves of no length at once is found out", "[serial][pacer]") {
  // A delta at the file's pace: its probes always say there is room, and
  // the moves let go on their word wait for blocks.
  Linked s;
  s.holds_probes = false;
  s.run(300, 1);
  const int sent = s.probes_sent;
  // (A few moves, each let go on one probe's word, waited before: the
  // host's own stalls are not taken for such a printer.)
  CHECK(sent >= 1);
  CHECK(s.most_ahead <= static_cast<std::size_t>(s.blocks) + 2);
  s.most_ahead = 0;
  s.run(500, 1);
  CHECK(s.probes_sent == sent);
  CHECK(s.most_ahead <= static_cast<std::size_t>(s.blocks));
  CHECK(s.pacer.speed_factor() <= 1.0 + 1e-9);
}

TEST_CASE("probe credit: probes that find room double the moves they let go, a late one puts it back to one, a move that waited stops the doubling", "[serial][pacer]") {
  ProbeCredit c;
  CHECK(c.due());
  CHECK(c.answered(true, true, 16) == 0);  // the one move the model frees
  CHECK(c.answered(true, true, 16) == 1);
  CHECK(c.left() == 1);
  CHECK_FALSE(c.due());
  CHECK(c.take());
  CHECK_FALSE(c.take());
  CHECK(c.due());
  CHECK(c.answered(true, true, 16) == 3);
  CHECK(c.answered(true, true, 16) == 7);  // (the 3 not taken stay)
  CHECK(c.left() == 10);
  while (c.left() > 2) CHECK(c.take());
  CHECK(c.due());  // a quarter left: the next probe goes ahead of them
  CHECK(c.answered(true, true, 16) == 15);
  CHECK(c.left() == 15);  // never more than the planner holds
  CHECK(c.answered(true, true, 16) == 15);
  CHECK(c.answered(false, true, 16) == 0);  // a late probe: back to one
  CHECK(c.left() == 0);
  CHECK(c.answered(true, true, 16) == 0);
  CHECK(c.answered(true, true, 16) == 1);
  CHECK(c.answered(true, true, 16) == 3);
  c.full();  // a move ahead of the next probe waited for a block: none left
  CHECK(c.left() == 0);
  CHECK(c.answered(true, true, 16) == 7);  // the probe found room: no more than last time
  CHECK(c.answered(true, true, 16) == 7);
  CHECK(c.answered(true, true, 16) == 15);
}

TEST_CASE("pacer: behind a link, probes to a printer twice as fast confirm the model it learnt and go few", "[serial][pacer]") {
  // A move's line takes most of its block on the wire at 2 x: a probe sent
  // as the model fills the planner arrives with little of the block it
  // waits for left, and its answer, as the model said, comes soon after it
  // arrived. Taken for room, each such probe put the next one with the
  // next held move (1761 to 1778 probes for these 3000 moves); as the
  // model said, the next ones are spaced (probe_spacing.hpp).
  // (Answers' way back, a line's time on the wire.)
  const std::pair<double, double> links[] = {{0.02, 0.35}, {0.02, 0.4}, {0.1, 0.35}};
  for (auto [back, link] : links) {
    INFO("answers " << back << " s back, lines " << link << " s on the wire");
    Linked s;
    s.factor = 2;
    s.link = link;
    s.back = back;
    AgainstUnpaced r = against_unpaced(s, 3000);
    Linked paced = s;
    paced.run(3000, 1);
    INFO(paced.probes_sent << " probes, factor " << paced.pacer.speed_factor() << ", paced " << r.paced_time
                           << " s against " << r.unpaced_time << " s unpaced");
    CHECK(paced.probes_sent <= 300);
    // Within 2 % of the printer, never above it (Pacer::kShownMargin).
    CHECK(paced.pacer.speed_factor() <= 2);
    CHECK(paced.pacer.speed_factor() >= 1.96);
    CHECK(r.paced_time <= 1.05 * r.unpaced_time);
    CHECK(r.paced_starved <= r.unpaced_starved + 0.01 * r.unpaced_time);
    CHECK(r.paced_ahead <= static_cast<std::size_t>(s.blocks + 2));
  }
}
