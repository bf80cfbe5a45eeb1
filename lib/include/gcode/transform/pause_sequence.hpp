#pragma once
// The pause and the resume of a print, as G-code lines built from the machine
// state at the point where printing stops.
//
// Shared by gc-pause-at (which writes the lines into the file at a layer
// boundary) and gc-send (which sends them when the user asks for a pause).
// Both only know a MachineState, so that is all this needs.
//
// What a good pause does (background.md §1) and what Cura's PauseAtHeight got
// wrong (issue 4) decide the shape:
//   pause:  retract (unless the file already did), lift, park at the back,
//           optional unload, standby temperature, messages, then the wait;
//   resume: heat and wait, optional reload/purge/prime at the park position,
//           travel back at the safe height, go down to exactly the Z the
//           file was at (a Z-hop height included: the next lines assume it),
//           unretract the same amount the same way, then restore the E
//           coordinate, G90/G91, M82/M83 and F, so the file carries on as if
//           nothing happened.
// Extrusion is written in the file's own E mode: forcing M82 on a relative
// file was Cura bug #5130.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/line_builder.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/transform/stream_tracker.hpp"  // RetractionTracker, for PausePoint
#include "gcode/transform/transition.hpp"

namespace gcode {

// What makes the printer (or its host) wait.
enum class PauseMethod : std::uint8_t {
  M0,         // Marlin/Prusa: wait for the user, with a message on the screen
  M1,         // the same, "optional stop"
  M25,        // pause the SD print (Marlin, RepRapFirmware)
  M125,       // Marlin ADVANCED_PAUSE: park and wait
  M226,       // RepRapFirmware: synchronous pause
  M600,       // filament change (the firmware unloads/reloads itself)
  M601,       // Prusa firmware: pause print
  HostPause,  // "@pause": OctoPrint, Repetier and gc-send pause the stream
  Klipper,    // "PAUSE": Klipper macro (needs [pause_resume] and a PAUSE macro)
  Dwell,      // G4 S<seconds>: a timed wait, no user action
  Custom,     // the user's own lines
  None,       // nothing: the caller waits itself (gc-send)
};

// Parses "M0", "m600", "@pause", "PAUSE", "G4", "custom:...", "none".
// `custom_text` receives the text after "custom:". Returns false when unknown.
bool parse_pause_method(std::string_view text, PauseMethod& method, std::string& custom_text);
std::string_view pause_method_name(PauseMethod method);

struct PauseConfig {
  // Speeds are mm/s (what users and slicers think in); lengths mm.
  double retract = 2;          // 0 = do not retract
  double retract_speed = 35;
  double unretract_speed = 35;
  double lift = 2;             // relative to the highest of the current Z and what was printed
  double z_speed = 10;
  double min_park_z = 0;       // 0 = no minimum
  double max_z = 0;            // printer's Z limit; 0 = unknown (no cap)
  double park_x = 0;
  double park_y = 0;
  // false: no park position is known (a file that does not say how big the
  // bed is): the block retracts and lifts where the head is, with no travel,
  // and the resume comes straight down. Lifted, the nozzle is off the part.
  bool park = true;
  double travel_speed = 60;
  bool wait_for_moves = false; // M400 before the wait
  bool standby = false;        // set standby_temp while waiting
  double standby_temp = 0;
  bool wait_for_heat = true;   // resume with M109 (wait) rather than M104
  double resume_temp = 0;      // used when the file never set a hotend temperature
  std::string message;         // M117, or the text of M0/M1; empty = none
  std::string host_message;    // M118; empty = none
  bool beep = false;
  double beep_ms = 1000;
  double beep_hz = 440;
  double stepper_hold = 0;     // seconds for M84 S (0 = leave as is)
  double unload = 0, unload_speed = 50;
  double reload = 0, reload_speed = 25;
  double purge = 0, purge_speed = 3;
  double prime = 0, prime_speed = 3;
  PauseMethod method = PauseMethod::M0;
  std::string custom_wait;     // lines of PauseMethod::Custom ('\n' separated)
  double dwell_seconds = 60;   // PauseMethod::Dwell
  std::string before_wait;     // the user's lines just before the wait
  std::string after_wait;      // and just after it
};

// Long unloads go in chunks of kMaxExtrudeChunk (transition.hpp).

// Where printing stops, beyond the machine state.
struct PausePoint {
  const MachineState& state;
  // mm of filament the file itself has already retracted with E moves and
  // not yet pushed back (RetractionTracker); 0 when unknown.
  double pending_retraction = 0;
  // The highest Z anything was printed at so far; the head travels above it.
  // Below the current Z (or 0) it is ignored.
  double top_z = 0;
  // The input's decimals per letter: computed numbers (E - 2, Z + lift, the
  // park position, feed rates) are written with no more. Null: X/Y/Z 3, E 5, F 0.
  const Precision* precision = nullptr;
};

struct PauseBlock {
  std::vector<std::string> pause;   // up to and including the wait command
  std::vector<std::string> resume;  // everything after the wait
  double safe_z = 0;                // the height the head travels at
  double park_z = 0;
  double net_filament = 0;          // what the lines push in total (mm)
};

// Builds both halves. Throws std::invalid_argument when the state cannot be
// resumed exactly (position unknown, inch units).
PauseBlock build_pause(const PausePoint& point, const PauseConfig& config);

}  // namespace gcode
