// The E mode of a file that never says M82/M83 (core/e_mode.hpp): the
// file's own command wins, then its config comment (tail before head), then
// how its E values move; too little to go on is the firmware's default.
#include <catch2/catch.hpp>

#include <string>

#include "gcode/core/e_mode.hpp"

using gcode::EModeChoice;
using gcode::guess_e_mode;

namespace {

// `n` extruding moves whose E climbs (absolute) or repeats small amounts
// (relative), with every `drop_every`-th one smaller than the one before.
std::string moves(int n, bool relative, int drop_every = 0) {
  std::string s;
  double e = 0;
  for (int i = 1; i <= n; ++i) {
    double v = 0;
    if (relative) {
      v = i % 2 == 0 ? 0.05 : 0.08;
    } else {
      e += 0.5;
      v = e;
      if (drop_every > 0 && i % drop_every == 0) v = e - 2;  // a wipe's retraction
    }
    s += "G1 X" + std::to_string(i) + " Y10 E" + std::to_string(v) + "\n";
  }
  return s;
}

}  // namespace

TEST_CASE("e mode: the file's own M82 or M83 settles it", "[e_mode]") {
  for (const char* cmd : {"M82", "M83", "m83 ; relative"}) {
    auto g = guess_e_mode("G28\n" + moves(30, true) + cmd + "\n", "; use_relative_e_distances = 1\n");
    CHECK(g.file_sets_mode);
    CHECK_FALSE(g.guessed);
    CHECK_FALSE(g.relative);
  }
  // In a comment it is no command.
  auto g = guess_e_mode("; M83\n" + moves(3, true), "");
  CHECK_FALSE(g.file_sets_mode);
}

TEST_CASE("e mode: the slicer's config comment, the tail's before the head's", "[e_mode]") {
  auto rel = guess_e_mode(moves(50, false), "; use_relative_e_distances = 1\n");
  CHECK(rel.guessed);
  CHECK(rel.relative);  // the config wins over E values that look absolute
  CHECK(rel.reason == "its config says use_relative_e_distances = 1");
  auto abs = guess_e_mode(moves(50, true), "; use_relative_e_distances = 0\n");
  CHECK(abs.guessed);
  CHECK_FALSE(abs.relative);
  CHECK(abs.reason == "its config says use_relative_e_distances = 0");
  auto head = guess_e_mode("; use_relative_e_distances = 1\n" + moves(2, false), "");
  CHECK(head.guessed);
  CHECK(head.relative);
  auto both = guess_e_mode("; use_relative_e_distances = 1\n", "; use_relative_e_distances = 0\n");
  CHECK_FALSE(both.relative);
  // The key with nothing after it says nothing.
  auto cut = guess_e_mode(moves(2, false), "; use_relative_e_distances = ");
  CHECK_FALSE(cut.guessed);
}

TEST_CASE("e mode: climbing E values are absolute, jumping ones relative", "[e_mode]") {
  auto abs = guess_e_mode(moves(40, false), "");
  CHECK(abs.guessed);
  CHECK_FALSE(abs.relative);
  CHECK(abs.reason == "0 of 39 extruding moves have a smaller E than the one before (a growing coordinate)");
  auto rel = guess_e_mode(moves(40, true), "");
  CHECK(rel.guessed);
  CHECK(rel.relative);
  CHECK(rel.reason == "20 of 39 extruding moves have a smaller E than the one before (relative amounts)");
}

TEST_CASE("e mode: a quarter of falling values is the border", "[e_mode]") {
  // 13 moves: 12 pairs. Every 4th falls: 3 drops, 3 * 4 = 12, not > 12.
  auto three = guess_e_mode(moves(13, false, 4), "");
  CHECK(three.reason.rfind("3 of 12 ", 0) == 0);
  CHECK_FALSE(three.relative);
  // Every 3rd falls: 4 drops, 16 > 12.
  auto four = guess_e_mode(moves(13, false, 3), "");
  CHECK(four.reason.rfind("4 of 12 ", 0) == 0);
  CHECK(four.relative);
}

TEST_CASE("e mode: G92 E resets are not drops, travel and bare E are not counted", "[e_mode]") {
  std::string s;
  for (int layer = 0; layer < 10; ++layer) s += "G92 E0\n" + moves(3, false);
  s += "G1 E-2 F2100\nG0 X5 Y5\nG1 Z0.4\n";
  auto g = guess_e_mode(s, "");
  CHECK(g.guessed);
  CHECK_FALSE(g.relative);
  // 10 runs of 3 moves: 2 pairs each, the G92 breaks the chain.
  CHECK(g.reason.rfind("0 of 20 ", 0) == 0);
}

TEST_CASE("e mode: too few extruding moves leave the firmware's default", "[e_mode]") {
  auto g = guess_e_mode(moves(10, true), "");  // 9 pairs
  CHECK_FALSE(g.guessed);
  CHECK_FALSE(g.relative);
  CHECK(g.reason == "too few extruding moves to tell");
  auto enough = guess_e_mode(moves(11, true), "");  // 10 pairs
  CHECK(enough.guessed);
  CHECK(enough.relative);
  auto empty = guess_e_mode("", "");
  CHECK_FALSE(empty.guessed);
  CHECK_FALSE(empty.file_sets_mode);
}

TEST_CASE("e mode: parse_e_mode takes the three names only", "[e_mode]") {
  EModeChoice c = EModeChoice::Absolute;
  CHECK(gcode::parse_e_mode("auto", c));
  CHECK(c == EModeChoice::Auto);
  CHECK(gcode::parse_e_mode("relative", c));
  CHECK(c == EModeChoice::Relative);
  CHECK(gcode::parse_e_mode("absolute", c));
  CHECK(c == EModeChoice::Absolute);
  CHECK_FALSE(gcode::parse_e_mode("Relative", c));
  CHECK_FALSE(gcode::parse_e_mode("rel", c));
  CHECK_FALSE(gcode::parse_e_mode("", c));
  CHECK(c == EModeChoice::Absolute);  // unchanged on failure
}

TEST_CASE("e mode: read_e_mode, the one decision every tool makes from --e-mode and the guess", "[e_mode]") {
  const auto relative_file = guess_e_mode(moves(30, true), "");
  REQUIRE(relative_file.guessed);
  // auto: the guess, with a warning naming the input and the reason.
  auto r = gcode::read_e_mode(EModeChoice::Auto, relative_file, "part.gcode");
  CHECK_FALSE(r.file_sets_mode);
  CHECK(r.relative);
  CHECK(r.warning == "part.gcode never sets the E mode (M82/M83); reading its E values as relative: " +
                         relative_file.reason + " (--e-mode relative|absolute to say)");
  // Said by the user: that, without a word, whatever the guess.
  for (EModeChoice said : {EModeChoice::Relative, EModeChoice::Absolute}) {
    auto told = gcode::read_e_mode(said, relative_file, "part.gcode");
    CHECK(told.relative == (said == EModeChoice::Relative));
    CHECK(told.warning.empty());
  }
  // Too little to go on: absolute, silently; the file's own M83: nothing to set.
  auto few = gcode::read_e_mode(EModeChoice::Auto, guess_e_mode(moves(5, true), ""), "part.gcode");
  CHECK_FALSE(few.relative);
  CHECK(few.warning.empty());
  auto own = gcode::read_e_mode(EModeChoice::Relative, guess_e_mode("M83\n" + moves(30, false), ""), "part.gcode");
  CHECK(own.file_sets_mode);
  CHECK(own.warning.empty());
}
