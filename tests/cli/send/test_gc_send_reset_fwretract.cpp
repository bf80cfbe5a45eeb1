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

}  // namespace

TEST_CASE("gc-send: a printer reset in a print with firmware retraction (G10/G11) primes as after one and comes back "
          "retracted where the print was",
          "[gc-send][reset]") {
  const std::string& file = gctest::pieces_of("cura_pegs_0.2_rel_fwretract.gcode", 9000);
  auto expected = gctest::commands_of(gctest::read_file(file));
  int retracted_targets = 0;
  for (int line : {2500, 4000, 5500, 7000, 8500}) {
    INFO("reset at line " << line);
    // (--no-pace: no pace probes among the numbers, so the reset lands at
    // the input's command `line`, in the layers.)
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
    retracted_targets += f.back_retracted ? 1 : 0;
  }
  INFO("resets whose way back ended retracted: " << retracted_targets);
  CHECK(retracted_targets > 0);
}
