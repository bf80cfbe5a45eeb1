#pragma once
// Shared by the tests of a print resumed after a printer reset: what
// gc-virtual-printer's executed log, across all its sessions, says ran.
//
// A reset note names the planner blocks the reset lost: logged (they had
// entered the planner) but never run. What ran is then the input's commands
// up to some point, the resume sequence, and the input again from a point
// at most that far back, to the end; the checks hold that against the input.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "serial_check.hpp"

namespace gctest {

struct RanCommand {
  long long number = 0;
  double x = 0, y = 0, z = 0, e = 0;  // the printer's position after it
  double time = 0;                    // simulated seconds
  std::string text;
  bool lost = false;                  // a planner block a reset lost: logged, never run
};

// The numbered commands of each session (split at the reset notes), the
// planner blocks each reset lost marked, and when each reset came.
struct ResetLog {
  std::vector<std::vector<RanCommand>> sessions;
  std::vector<double> reset_at;
};

inline ResetLog read_reset_log(std::string_view text) {
  ResetLog log;
  log.sessions.emplace_back();
  gcode::MemoryLineSplitter split(text);
  gcode::RawLine raw;
  while (split.next(raw)) {
    std::string line(raw.text);
    if (line.rfind("# reset at ", 0) == 0) {
      log.reset_at.push_back(std::stod(line.substr(11)));
      // "# reset at T: lost from the planner and queue N1 N2; N3"
      std::set<long long> lost;
      std::istringstream words(line.substr(line.find("queue") + 5, line.find(';') - line.find("queue") - 5));
      std::string w;
      while (words >> w) lost.insert(std::stoll(w.substr(1)));
      for (RanCommand& c : log.sessions.back()) c.lost = lost.count(c.number) > 0;
      log.sessions.emplace_back();
      continue;
    }
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    RanCommand c;
    fields >> c.time >> c.number >> c.x >> c.y >> c.z >> c.e;
    std::getline(fields, c.text);
    c.text.erase(0, c.text.find_first_not_of('\t'));
    if (c.number >= 0) log.sessions.back().push_back(std::move(c));
  }
  return log;
}

// gc-send's own lines: a pace probe, a question.
inline bool is_own_line(const RanCommand& c) { return c.text == "G1" || c.text == "M105"; }

inline bool only_own_after(const std::vector<RanCommand>& ran, std::size_t i) {
  for (; i < ran.size(); ++i)
    if (!is_own_line(ran[i])) return false;
  return true;
}

// How a session's commands from `j` follow the input from `q`: to the
// session's end (and the final M400), with at most one block of lines of
// gc-send's own inside when `own_block` (a pause's block and return).
// Returns the indices into the session of each input command, or empty.
inline std::vector<std::size_t> follow_input(const std::vector<RanCommand>& ran, std::size_t j,
                                             const std::vector<SentCommand>& expected, std::size_t q, bool own_block) {
  std::vector<std::size_t> at;
  std::size_t i = j, k = q;
  bool skipped = false;
  while (i < ran.size() && k < expected.size()) {
    if (ran[i].text == expected[k].text) {
      at.push_back(i++);
      ++k;
      continue;
    }
    if (is_own_line(ran[i])) {
      ++i;
      continue;
    }
    if (!own_block || skipped || at.size() < 2) return {};
    skipped = true;
    while (i < ran.size() && ran[i].text != expected[k].text) ++i;
  }
  if (at.empty()) return {};
  if (i == ran.size()) return at;
  // The input ends; gc-send's M400 waits for the last move, and while it
  // waits gc-send may still ask (numbered, so the log shows it).
  if (k == expected.size() && ran[i].text == "M400" && only_own_after(ran, i + 1)) return at;
  return {};
}

inline bool is_extruding_move(const RanCommand& before, const RanCommand& c) {
  return c.text.rfind("G1", 0) == 0 && c.e > before.e + 1e-9 && (c.x != before.x || c.y != before.y);
}

// Moves (G0-G3 with an axis or E) among expected[from, to): what a
// printer's buffers hold is counted in moves; the commands between them
// (M204, M73, a lone F) ran as they were read and may go again with them.
inline std::size_t moves_among(const std::vector<SentCommand>& expected, std::size_t from, std::size_t to) {
  std::size_t moves = 0;
  for (std::size_t k = from; k < to && k < expected.size(); ++k) {
    const std::string& t = expected[k].text;
    const bool motion = t.size() > 2 && t[0] == 'G' && t[1] >= '0' && t[1] <= '3' && t[2] == ' ';
    if (motion && t.find_first_of("XYZE", 2) != std::string::npos) ++moves;
  }
  return moves;
}

struct ResetFigures {
  int resets = 0;
  int redone_moves = 0;      // input moves that ran twice
  double redone_mm = 0;      // ... their length
  double back_after_s = 0;   // simulated seconds from the last reset to the first input move again
};

// The resume sequence (the lines before the input goes on): no Z homing
// once something was printed, the bed then the hot end waited for before
// anything is extruded, every X/Y move above what was printed.
inline void check_sequence(const std::vector<RanCommand>& ran, std::size_t j, RanCommand before, double top) {
  int bed = -1, hot = -1;
  for (std::size_t i = 0; i < j; ++i) {
    const RanCommand& c = ran[i];
    INFO("sequence line " << i << ": " << c.text);
    CHECK((c.text.rfind("G28", 0) != 0 || c.text == "G28 X Y" || top == 0));
    if (c.text.rfind("M190", 0) == 0 && bed < 0) bed = static_cast<int>(i);
    if (c.text.rfind("M109", 0) == 0 && hot < 0) hot = static_cast<int>(i);
    // (The first line's row is the reset printer's X0 Y0 E0: no move, and
    // nothing pushed, though the print's E before the reset may have stood
    // below 0, retracted after a G92 E0.)
    if (c.e > before.e + 1e-9 && i > 0) CHECK((hot >= 0 && bed < hot));
    if ((c.x != before.x || c.y != before.y) && i > 0) CHECK(c.z >= top - 1e-6);
    before = c;
  }
}

// Every input command ran once, in order, except the re-run after each
// reset: at most `buffered` moves back (the planner's 16 moves and the
// queue's 4), covering every one the reset lost; each resume sequence passes
// check_sequence; the re-run commands end where they did the first time (X,
// Y, Z and E: E per move equal to the input's). `pause`: lines of gc-send's
// own (a pause's block and return) may come between two input commands.
inline ResetFigures require_resumed(const std::string& log_text, const std::vector<SentCommand>& expected,
                                    std::size_t buffered = 20, bool pause = false) {
  ResetLog log = read_reset_log(log_text);
  ResetFigures f;
  f.resets = static_cast<int>(log.reset_at.size());
  std::vector<const RanCommand*> first_run(expected.size(), nullptr);  // where each input command first ran
  std::size_t p = 0;          // input commands sent so far
  std::size_t must = 0;       // the first of them that may not have run
  double top = 0;             // the highest Z extruded at
  RanCommand last;
  for (std::size_t s = 0; s < log.sessions.size(); ++s) {
    const auto& ran = log.sessions[s];
    INFO("session " << s);
    std::size_t j = 0, q = 0;
    std::vector<std::size_t> at;
    for (j = 0; j < ran.size() && at.empty(); ++j)
      for (q = p > 400 ? p - 400 : 0; q <= must && at.empty(); ++q) at = follow_input(ran, j, expected, q, pause);
    if (ran.empty() && s + 1 == log.sessions.size()) break;
    if (at.empty() && s > 0 && s + 1 < log.sessions.size()) {
      // The printer reset again inside the resume sequence, before any
      // command of the input ran: the next session goes back as far.
      check_sequence(ran, ran.size(), last, top);
      if (!ran.empty()) last = ran.back();
      continue;
    }
    INFO("input commands sent before it " << p << ", the first that may not have run " << must);
    REQUIRE(!at.empty());
    --j;
    --q;
    if (s == 0) REQUIRE((q == 0 && j == 0));
    REQUIRE(q <= must);  // nothing the reset lost is left out
    REQUIRE(moves_among(expected, q, must) <= buffered);
    if (s > 0) check_sequence(ran, j, last, top);
    std::size_t next_must = q + at.size();
    for (std::size_t n = 0; n < at.size(); ++n) {
      const std::size_t k = q + n;
      const RanCommand& c = ran[at[n]];
      INFO("input command " << k << ": " << c.text);
      if (c.lost) {
        next_must = std::min(next_must, k);
      } else if (first_run[k] == nullptr) {
        first_run[k] = &c;
      } else {
        const RanCommand& once = *first_run[k];
        CHECK(std::abs(c.x - once.x) < 1e-4);
        CHECK(std::abs(c.y - once.y) < 1e-4);
        CHECK(std::abs(c.z - once.z) < 1e-4);
        CHECK(std::abs(c.e - once.e) < 1e-4);
        const RanCommand& prev = *first_run[k > 0 && first_run[k - 1] != nullptr ? k - 1 : k];
        if (once.x != prev.x || once.y != prev.y) {
          ++f.redone_moves;
          f.redone_mm += std::hypot(once.x - prev.x, once.y - prev.y);
        }
      }
      if (at[n] > 0 && is_extruding_move(ran[at[n] - 1], c)) top = std::max(top, c.z);
      last = c;
    }
    if (s > 0) f.back_after_s = ran[j].time - log.reset_at[s - 1];
    p = q + at.size();
    must = next_must;
  }
  REQUIRE(p == expected.size());
  const auto& final_session = log.sessions.back();
  auto last_not_own = std::find_if(final_session.rbegin(), final_session.rend(),
                                   [](const RanCommand& c) { return !is_own_line(c); });
  REQUIRE(last_not_own != final_session.rend());
  CHECK(last_not_own->text == "M400");
  return f;
}

}  // namespace gctest
