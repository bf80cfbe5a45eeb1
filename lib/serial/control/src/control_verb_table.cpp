// The table of gc-send's control verbs (control_verbs.hpp), beside the
// PrintControl actions its rows call: control_verbs() is PrintControl's
// friend. (Its own file: the table's reader, control_verbs.cpp, must not
// include PrintControl, which takes what it reads.)
#include <charconv>
#include <string>

#include <fmt/format.h>

#include "gcode/core/number.hpp"
#include "gcode/core/text.hpp"
#include "gcode/serial/control/control_verbs.hpp"
#include "gcode/serial/control/print_control.hpp"

namespace gcode::serial {

namespace {

// A speed factor: above 0, at most 100 (1 = as sliced).
std::string read_factor(std::string_view text, ControlCommand& command) {
  double f = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), f);
  if (ec != std::errc() || end != text.data() + text.size() || !(f > 0) || f > 100)
    return fmt::format("speed: '{}' is not a factor above 0 (1 = as sliced)", text);
  command.number = f;
  return std::string();
}

}  // namespace

std::span<const ControlVerb> control_verbs() {
  using C = const ControlCommand&;
  static constexpr ControlVerb kVerbs[] = {
      {.name = "pause",
       .help = "finish the layer (the rest rushed, --rush), then park until resume",
       .handle = [](PrintControl& p, C) { p.request_pause("pause", false); }},
      {.name = "pause now",
       .help = "stop at the next command boundary, then park",
       .handle = [](PrintControl& p, C) { p.request_pause("pause now", true); }},
      {.name = "resume",
       .help = "return exactly to where the print stopped and go on",
       .handle = [](PrintControl& p, C) { p.resume(); }},
      {.name = "speed",
       .argument = "F",
       .help = "run the following moves at F times the file's speed (1 = as sliced)",
       .read = read_factor,
       .handle = [](PrintControl& p, C c) { p.set_speed(c.number); },
       .journal_field = "speed",
       .journal = [](const PrintControl& p) { return fmt::format("{:g}", p.speed()); },
       .restore =
           [](PrintControl& p, std::string_view kept) {
             double f = 1;
             if (parse_number(kept, f)) p.restore_speed(f);
           }},
      {.name = "gcode",
       .argument = "LINE",
       .help = "while paused: send one command (resume puts back what it changed)",
       .handle = [](PrintControl& p, C c) { p.user_gcode(c.argument); }},
      {.name = "cancel",
       .help = "safe end: retract, lift, park, --cancel-gcode (heaters, fan, motors off)",
       .handle = [](PrintControl& p, C) { p.cancel(); }},
      {.name = "cancel object",
       .argument = "ID|NAME",
       .help = "leave objects out from the next line on (several may follow), host side; print on",
       .handle =
           [](PrintControl& p, C c) {
             if (!p.cancelled()) p.objects_.cancel(c.argument);
           },
       .journal_field = "cancelled",
       .journal = [](const PrintControl& p) { return p.objects_.journal_text(); },
       .restore = [](PrintControl& p, std::string_view kept) { p.objects_.exclude(split_lines(kept), "the journal", true); }},
      {.name = "objects",
       .help = "list the objects named so far: id, name, printing, kept or cancelled",
       .handle =
           [](PrintControl& p, C) {
             for (const std::string& line : p.objects_.listing()) p.diag_.report(line);
           }},
      {.name = "status",
       .help = "one progress line",
       .handle =
           [](PrintControl& p, C) {
             if (p.on_status) p.on_status();
           }},
      {.name = "insert",
       .argument = "FILE",
       .help = "while paused: send FILE's commands (resume still returns exactly)",
       .handle = [](PrintControl& p, C c) { p.insert_file(c.argument); }},
      {.name = "swap",
       .argument = "FILE",
       .help = "go on with the part re-sliced, above what is printed (gc-relayer's rules)",
       .handle = [](PrintControl& p, C c) { p.request_swap(c.argument); }},
  };
  return kVerbs;
}

}  // namespace gcode::serial
