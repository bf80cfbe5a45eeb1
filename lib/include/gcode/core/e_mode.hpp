#pragma once
// The E mode of a file that never says M82 or M83.
//
// Some slicers and Klipper set-ups leave the E mode to the printer's start
// macro: the file has relative E amounts and no M83. Read as absolute (the
// firmware's default), such a file seems to print a fraction of its
// filament and retract most of it. Before streaming, the tool looks at the
// file: its own M82/M83 (then nothing is guessed), the slicer's config
// comments (`; use_relative_e_distances = 1`), and else how its E values
// move. Absolute E values climb between G92 resets and fall only for a
// retraction; relative amounts are small and jump up and down.
#include <functional>
#include <string>
#include <string_view>

namespace gcode {

enum class EModeChoice : unsigned char { Auto, Absolute, Relative };

struct EModeGuess {
  bool file_sets_mode = false;  // the head has an M82/M83
  bool guessed = false;         // the file never says: relative is the guess below
  bool relative = false;
  std::string reason;           // for the message
};

// `head`: the start of the file (up to some thousand extrusions); `tail`: its
// end (PrusaSlicer's config block), may be empty.
EModeGuess guess_e_mode(std::string_view head, std::string_view tail);

// Parses "relative", "absolute" or "auto". Returns false for anything else.
bool parse_e_mode(std::string_view text, EModeChoice& choice);

// How a tool reads a file, from --e-mode and what guess_e_mode found: every
// tool that reads G-code decides alike (filters, gc-send).
struct EModeReading {
  bool file_sets_mode = false;  // the file's own M82/M83 decide: nothing to set
  bool relative = false;        // else the E mode to start in
  std::string warning;          // a guess the user did not confirm ("" when none)
};
// `name`: the input as messages call it ("part.gcode", "standard input").
EModeReading read_e_mode(EModeChoice choice, const EModeGuess& guess, std::string_view name);
// The same for open file `fd`, guessed from its two ends when it is a
// regular file (its offset not moved), else from what `read_ahead` gives:
// the start of a pipe that the caller keeps for its pipeline (none: nothing
// to guess from).
EModeReading read_e_mode_of(int fd, EModeChoice choice, std::string_view name,
                            const std::function<std::string_view()>& read_ahead = {});

}  // namespace gcode
