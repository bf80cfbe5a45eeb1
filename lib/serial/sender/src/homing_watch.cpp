#include "gcode/serial/sender/homing_watch.hpp"

#include <fmt/format.h>

#include "gcode/core/line.hpp"
#include "gcode/core/text.hpp"
#include "gcode/serial/protocol/protocol.hpp"

namespace gcode::serial {

bool is_homing_command(const Line& line) { return line.is('G', 28) && line.subcode < 0; }

std::string HomingWatch::error(std::string_view message, std::string_view command, bool homing) const {
  if (homing || says_homing_failed(message))
    return fmt::format("homing failed: the printer answered {} with \"{}\"",
                       command.empty() ? std::string_view("a command") : trim(command), trim(message));
  return HomingWatch::message(message);
}

std::string HomingWatch::message(std::string_view text) const {
  if (!homed_ || !says_not_homed(text)) return {};
  return fmt::format("the printer lost its homing (\"{}\"): every move from here on would be refused", trim(text));
}

}  // namespace gcode::serial
