// gc-send against gc-virtual-printer resetting in a print that retracts
// with the firmware (G10/G11: Cura's firmware retraction). A printer that
// reset starts unretracted, its nozzle oozed while it heated: the way back
// primes as after a firmware retraction (Marlin's 3 mm when the file sets
// no M207), and puts the firmware back into its retracted state where the
// print stood retracted, so that the print's next G11 is not ignored. The
// executed log is read as Marlin's FWRETRACT moves the filament (G10 pulls
// back 3 mm unless retracted, G11 pushes them back only when retracted):
// from each reset to the first extruding move the printer pushed exactly
// the prime, and no G11 came while unretracted.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "pty_run.hpp"
#include "reset_check.hpp"
#include "test_support.hpp"

namespace {

constexpr double kFirmwareRetraction = 3;  // mm: Marlin's FWRETRACT default (the file has no M207)

struct Filament {
  double pushed = 0;  // mm since the reset, up to the first extruding move
  bool retracted = false;
  int ignored_g11 = 0;
  bool back_retracted = false;  // the way back's prime was followed by a G10
};

// One session after a reset, as the firmware moves the filament.
Filament after_reset(const std::vector<gctest::RanCommand>& ran) {
  Filament f;
  bool printing = false, primed = false;
  for (std::size_t i = 1; i < ran.size(); ++i) {
    const gctest::RanCommand& c = ran[i];
    const gctest::RanCommand& before = ran[i - 1];
    double pushed = 0;
    if (c.text == "G10") {
      if (!f.retracted) pushed = -kFirmwareRetraction;
      // Right after the prime (the first E-only push): the way back's own.
      if (i >= 2 && primed && !printing && before.e > ran[i - 2].e && before.x == ran[i - 2].x && before.y == ran[i - 2].y)
        f.back_retracted = true;
      f.retracted = true;
    } else if (c.text == "G11") {
      if (f.retracted) pushed = kFirmwareRetraction;
      if (!f.retracted) ++f.ignored_g11;
      f.retracted = false;
    } else if (c.text.rfind("G92", 0) != 0) {
      pushed = c.e - before.e;
      if (pushed > 0) primed = true;
    }
    if (!printing && gctest::is_extruding_move(before, c)) printing = true;
    if (!printing) f.pushed += pushed;
  }
  return f;
}

// Whether the firmware had the filament retracted after input line `line`
// (the last G10 or G11 up to it).
bool retracted_after(const std::string& text, std::uint64_t line) {
  bool retracted = false;
  std::uint64_t n = 0;
  for (const std::string& l : gctest::split_lines(text)) {
    if (++n > line) break;
    if (l.rfind("G10", 0) == 0) retracted = true;
    if (l.rfind("G11", 0) == 0) retracted = false;
  }
  return retracted;
}

}  // namespace

TEST_CASE("gc-send: a printer reset in a print with firmware retraction (G10/G11) primes as after one and comes back "
          "retracted where the print was",
          "[gc-send][reset]") {
  const std::string& file = gctest::pieces_of("cura_pegs_0.2_rel_fwretract.gcode", 9000);
  auto expected = gctest::commands_of(gctest::read_file(file));
  const std::string text = gctest::read_file(file);
  int retracted_targets = 0;
  for (int line : {2500, 3200, 4000, 4700, 5500, 6200, 7000, 7700, 8500}) {
    INFO("reset at line " << line);
    // (--no-pace: no pace probes among the numbers; gc-send's questions of
    // an overdue answer are, on a loaded machine, so where the reset lands
    // in the input moves a little: the way back is judged against where it
    // went back to.)
    gctest::PtyRun r = gctest::send_through_pty(file, "--no-journal --no-pace",
                                                "--time-scale 200 --heat-rate 1000 --fault reset@line=" +
                                                    std::to_string(line));
    INFO(r.result.err);
    REQUIRE(r.result.status == 0);
    REQUIRE(gctest::require_resumed(r.log_text, expected).resets == 1);
    gctest::ResetLog log = gctest::read_reset_log(r.log_text);
    REQUIRE(log.sessions.size() == 2);
    Filament f = after_reset(log.sessions[1]);
    CHECK(std::abs(f.pushed - kFirmwareRetraction) < 1e-6);
    CHECK(f.ignored_g11 == 0);
    // "going back to line L of the input": the print stood after line L.
    const std::string going = "going back to line ";
    REQUIRE(r.result.err.find(going) != std::string::npos);
    const bool target_retracted =
        retracted_after(text, static_cast<std::uint64_t>(gctest::number_after(r.result.err, going)));
    CHECK(f.back_retracted == target_retracted);
    retracted_targets += target_retracted ? 1 : 0;
  }
  INFO("resets whose way back ended retracted: " << retracted_targets);
  CHECK(retracted_targets > 0);
}
