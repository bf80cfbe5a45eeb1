#pragma once
// The modal state of a Marlin-style printer, updated line by line.
//
// Coordinates are kept in millimetres in the file's own coordinate system (what
// an absolute X word means now); `offset` holds what G92 shifted, so
// machine position = position + offset. Filament is counted separately so a
// G92 E0 or a switch between M82 and M83 never changes how much was extruded.
//
// Positions are exact decimals (fixed.hpp): relative moves add up without
// drift, and a block that returns to a position or restores E writes the
// decimal the file is at. `position` holds the same values as doubles for
// geometry; MachineState::apply keeps the two equal.
#include <array>
#include <cstdint>

#include "gcode/core/fixed.hpp"
#include "gcode/core/line.hpp"

namespace gcode {

// Millimetres in the inch that G20 selects.
inline constexpr double kMmPerInch = 25.4;

enum Axis : int { kX = 0, kY = 1, kZ = 2, kE = 3 };

struct Vec4 {
  std::array<double, 4> v{};
  double& operator[](int i) { return v[static_cast<std::size_t>(i)]; }
  double operator[](int i) const { return v[static_cast<std::size_t>(i)]; }
};

enum class MoveKind : std::uint8_t {
  None,         // not a motion command
  Linear,       // G0 / G1
  Arc,          // G2 / G3
  Home,         // G28
  SetPosition,  // G92
  FirmwareRetract,
  FirmwareUnretract,
};

// What one line did to the machine.
struct Move {
  Move() = default;
  // Standing at `at` with feed rate `feed`: what every line starts from.
  // Built field by field: value-initialised and then overwritten, the 112
  // bytes were cleared with a rep stos on every line.
  Move(const Vec4& at, double feed) : start(at), end(at), feedrate(feed) {}

  MoveKind kind = MoveKind::None;
  Vec4 start;                 // file coordinates before the line (E: the E coordinate)
  Vec4 end;                   // after the line
  double filament = 0;        // mm of filament pushed (negative = retraction), whatever the E mode
  double length = 0;          // XYZ path length in mm (arc length for arcs)
  double xy_length = 0;
  double feedrate = 0;        // mm/min in effect for the move
  bool extruding = false;     // moves the head and pushes filament
  bool travel = false;        // moves the head, no filament
  bool z_changed = false;
  bool is_arc_clockwise = false;
  bool ignored = false;       // a malformed move the state did not apply
  // Z-hop: a non-extruding move that raises Z is a lift; the non-extruding
  // move that brings Z back down to where the lift began is the hop's return.
  // A lift followed by extrusion at the new height was a layer change instead.
  bool z_lift = false;
  bool z_hop_return = false;

  bool moves_head() const { return length > 0; }
  bool retraction() const { return filament < 0 && length == 0; }
  bool unretraction() const { return filament > 0 && length == 0; }
};

struct MachineState {
  Vec4 position;              // file coordinates, mm (exact[a].to_double())
  std::array<Fixed, 4> exact;   // file coordinates, mm, as exact decimals
  std::array<Fixed, 4> offset;  // G92 shift: machine = position + offset
  std::array<bool, 4> known{};  // whether each axis position is known (homed or set)
  double feedrate = 0;        // mm/min, modal F
  bool relative_xyz = false;  // G91
  bool relative_e = false;    // M83, or G91 (Marlin couples E to G90/G91)
  // Whether the file itself has said M82 or M83. Blocks a tool adds never
  // write an E mode a file did not set: they work in the mode in force.
  bool e_mode_set = false;
  // Marlin's G90/G91 also set the E mode. Off while the E mode comes from
  // outside the file (a printer's start macro, --e-mode): on Klipper and the
  // like G90 leaves E alone, and a file that never says M83 relies on that.
  bool e_follows_g90 = true;
  bool inches = false;        // G20
  bool firmware_retracted = false;  // G10 without G11 yet
  bool uses_firmware_retraction = false;  // a bare G10 or G11 has been seen
  int tool = 0;
  double filament_total = 0;  // net mm of filament pushed since the start
  // Heaters, fan and factors: the one record of them. Lines that set them
  // are read by read_heater_fan (below) here and wherever else they count.
  std::array<double, 8> hotend_target{};  // per tool: M104/M109 S|R, M568 P S, RepRapFirmware G10 P S
  double bed_target = 0;      // M140/M190 S|R
  double fan = 0;             // 0..255, the part fan: M106/M107 (P0)
  double speed_factor = 100;  // %, M220 S (B backs it up, R restores it)
  double flow_factor = 100;   // %, M221 S
  double speed_factor_backup = 100;
  bool lifted = false;        // Z raised by a non-extruding move, not yet back down or extruded at
  double lift_base_z = 0;     // the Z before that lift

  // Applies one line; returns what it did. Lines that are not motion change
  // modes (G90, M83, ...) and return a Move of kind None.
  Move apply(const Line& line);

  double machine(int axis) const { return (at(axis) + offset[static_cast<std::size_t>(axis)]).to_double(); }
  Fixed at(int axis) const { return exact[static_cast<std::size_t>(axis)]; }
  // Sets one axis (tests and stages that model a position of their own).
  void set(int axis, Fixed value) {
    exact[static_cast<std::size_t>(axis)] = value;
    position[axis] = value.to_double();
  }
};

// What a heater or fan line sets: one reading of M104/M109/M568/G10 P S,
// M140/M190, M141/M191 and M106/M107 for the machine state and for the
// settings a seam carries (carried_settings.hpp).
struct HeaterFanLine {
  enum class Kind : std::uint8_t { Bed, Chamber, Hotend, Fan };
  Kind kind = Kind::Hotend;
  int index = 0;  // tool or fan
  Fixed value;    // target or fan speed (0..255)
};

// Whether `line` sets a heater or a fan, and what; `tool` is the active
// tool (M104 without T). A line with no value to set (a bare M104) sets
// nothing; M106 without S is full speed.
bool read_heater_fan(const Line& line, int tool, HeaterFanLine& out);

// Whether two states describe the same machine: everything but the
// filament counter, which counts what a stream pushed, not where it is.
bool same_machine(const MachineState& a, const MachineState& b);

}  // namespace gcode
