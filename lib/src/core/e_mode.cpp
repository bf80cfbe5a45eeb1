#include "gcode/core/e_mode.hpp"

#include "gcode/core/file_ends.hpp"

#include "gcode/core/line.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/core/machine_state.hpp"

namespace gcode {

namespace {

// "; use_relative_e_distances = 1" in a PrusaSlicer / Slic3r / Orca config block.
int config_relative(std::string_view text) {
  constexpr std::string_view key = "; use_relative_e_distances = ";
  std::size_t at = text.rfind(key);
  if (at == std::string_view::npos || at + key.size() >= text.size()) return -1;
  return text[at + key.size()] == '1' ? 1 : 0;
}

}  // namespace

bool parse_e_mode(std::string_view text, EModeChoice& choice) {
  if (text == "auto") {
    choice = EModeChoice::Auto;
  } else if (text == "absolute") {
    choice = EModeChoice::Absolute;
  } else if (text == "relative") {
    choice = EModeChoice::Relative;
  } else {
    return false;
  }
  return true;
}

EModeGuess guess_e_mode(std::string_view head, std::string_view tail) {
  EModeGuess g;
  MemoryLineSplitter lines(head);
  RawLine raw;
  // E values of extruding-looking moves (XY and E), read as written.
  int pairs = 0, drops = 0, moves = 0;
  bool have_last = false;
  double last = 0;
  while (lines.next(raw)) {
    Line line = Line::parse(raw.text);
    if (line.kind != CommandKind::Standard) continue;
    if (line.is_m(82) || line.is_m(83)) {
      // Set before or soon after a purge line in the start code: the file
      // says its mode, the firmware's default covers what comes before.
      g.file_sets_mode = true;
      return g;
    }
    if (line.is_g(92) && line.has('E')) {
      have_last = false;
      continue;
    }
    if (!line.is_move() || !(line.has('X') || line.has('Y'))) continue;
    const Word* e = line.find('E');
    if (e == nullptr || !e->has_value) continue;
    double v = e->value();
    ++moves;
    if (have_last) {
      ++pairs;
      if (v < last) ++drops;
    }
    last = v;
    have_last = true;
  }
  int config = config_relative(tail);
  if (config < 0) config = config_relative(head);
  g.guessed = true;
  if (config >= 0) {
    g.relative = config == 1;
    g.reason = g.relative ? "its config says use_relative_e_distances = 1" : "its config says use_relative_e_distances = 0";
  } else if (pairs >= 10) {
    // Absolute: E falls only where a wipe retracts while moving (a few per
    // cent of moves). Relative: each amount is independent of the last.
    g.relative = drops * 4 > pairs;
    g.reason = std::to_string(drops) + " of " + std::to_string(pairs) + " extruding moves have a smaller E than the one before" +
               (g.relative ? " (relative amounts)" : " (a growing coordinate)");
  } else {
    g.guessed = false;  // too little to go on: the firmware's default, absolute
    g.reason = "too few extruding moves to tell";
  }
  return g;
}

EModeReading read_e_mode(EModeChoice choice, const EModeGuess& guess, std::string_view name) {
  EModeReading r;
  if (guess.file_sets_mode) {
    r.file_sets_mode = true;
    return r;
  }
  r.relative = choice == EModeChoice::Auto ? guess.guessed && guess.relative : choice == EModeChoice::Relative;
  if (choice == EModeChoice::Auto && guess.guessed)
    r.warning = std::string(name) + " never sets the E mode (M82/M83); reading its E values as " +
                (r.relative ? "relative" : "absolute") + ": " + guess.reason + " (--e-mode relative|absolute to say)";
  return r;
}

EModeReading read_e_mode_of(int fd, EModeChoice choice, std::string_view name,
                            const std::function<std::string_view()>& read_ahead) {
  FileEnds ends;
  if (read_file_ends(fd, 1 << 20, 1 << 16, ends)) return read_e_mode(choice, guess_e_mode(ends.head, ends.tail), name);
  return read_e_mode(choice, guess_e_mode(read_ahead ? read_ahead() : std::string_view(), {}), name);
}

}  // namespace gcode
