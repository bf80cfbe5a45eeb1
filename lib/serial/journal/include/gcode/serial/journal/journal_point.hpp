#pragma once
// A machine state as journal fields (journal.hpp), and back: what a resume
// needs to put the printer where the print was. Every state writes the same
// keys, so the journal's deltas hold only what a command changed (a G1:
// x, y, e); positions are exact decimals, as MachineState keeps them, so a
// state read back is the same machine (same_machine) as the one written.
//
//   x y z e          file coordinates        ox oy oz oe   G92 offsets
//   known            axes whose position is known ("xyz", "xy", "")
//   f                feed rate, mm/min       g91 m83 g20   modes (0/1)
//   emode eg90       the file set M82/M83; Marlin's G90 also sets E
//   fw               firmware retraction: "" unused, "in" used, "out" retracted
//   tool fil         active tool; net filament pushed since the start
//   hot bed fan      heater targets (hot: per tool, "215,0"), fan 0..255
//   m220 m220b m221  speed factor %, its M220 B backup, flow factor % (M221 S)
//   lift liftz       a z-hop is up (0/1), the Z it lifted from
//
// And for a resume after a reset (reset_sequence.hpp's ResumeTrack):
//   top retr prime   the highest Z extruded at, mm retracted, the longest retraction
//   restore          a line of such a resume: the n of the command it goes back to (0: none)
//   drained          1: once answered, every command up to it had run (an M400, G28, G29, G4,
//                    or where a resumed print went on: the printer had drained or reset by then)
#include <string>

#include "gcode/core/machine_state.hpp"
#include "gcode/serial/journal/journal_record.hpp"
#include "gcode/serial/protocol/reset_sequence.hpp"

namespace gcode::serial {

// `before`: the state `fields` holds already (the command before's): where
// the settings (offsets, known axes, modes, tool, heaters, fan, factors, a
// z-hop) are the same, only X Y Z E, the feed rate and the filament are
// written again.
void write_machine_fields(const MachineState& state, JournalFields& fields, const MachineState* before = nullptr);

// Fills `state` from `fields`; false (with `problem` naming the field) when
// one is missing or does not read as its kind.
bool read_machine_fields(const JournalFields& fields, MachineState& state, std::string& problem);

void write_track_fields(const ResumeTrack& track, long long restore, bool drained, JournalFields& fields);
// The field `drained` set: a walk back after a reset stops at this command.
void mark_drained(JournalFields& fields);
bool is_drained(const JournalFields& fields);
// A journal written before these fields reads as nothing extruded higher
// than the state's own Z, nothing retracted, no resume line.
ResumeTrack read_track_fields(const JournalFields& fields, const MachineState& state);

}  // namespace gcode::serial
