// A firmware's own state in the virtual printer (virtual_flavour_state.hpp):
// Klipper's shutdown keeps its reason until the board restarts, a
// FIRMWARE_RESTART is due once, Prusa's own pause ends once.
#include <catch2/catch.hpp>

#include "gcode/serial/sim/virtual_flavour_state.hpp"

using gcode::serial::FlavourState;

TEST_CASE("flavour state: a shutdown holds until the board restarts, a restart is due once", "[serial][virtual]") {
  FlavourState f;
  CHECK_FALSE(f.shut_down());
  f.shut_down_for("Shutdown due to M112 command");
  CHECK(f.shut_down());
  CHECK(f.shutdown_reason() == "Shutdown due to M112 command");
  CHECK_FALSE(f.take_restart());
  f.restart_after_ok();
  CHECK(f.take_restart());
  CHECK_FALSE(f.take_restart());
  f.restarted();
  CHECK_FALSE(f.shut_down());
}

TEST_CASE("flavour state: the user's answer ends an own pause once", "[serial][virtual]") {
  FlavourState f;
  CHECK_FALSE(f.take_resume());
  f.own_pause();
  CHECK(f.own_paused());
  CHECK(f.take_resume());
  CHECK_FALSE(f.own_paused());
  CHECK_FALSE(f.take_resume());
  // A restart ends it too, and keeps a restart already due.
  f.own_pause();
  f.restart_after_ok();
  f.restarted();
  CHECK_FALSE(f.own_paused());
  CHECK(f.take_restart());
}
