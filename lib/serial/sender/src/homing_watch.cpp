#include "gcode/serial/sender/homing_watch.hpp"

#include <fmt/format.h>

#include "gcode/core/text.hpp"
#include "gcode/serial/protocol/protocol.hpp"

namespace gcode::serial {

bool is_homing_command(std::string_view command) {
  std::string_view s = trim(command);
  if (s.size() < 3 || (s[0] != 'G' && s[0] != 'g')) return false;
  std::size_t i = 1;
  while (i < s.size() && s[i] == '0') ++i;  // "G028"
  if (s.substr(i, 2) != "28") return false;
  i += 2;
  return i == s.size() || !((s[i] >= '0' && s[i] <= '9') || s[i] == '.');
}

std::string HomingWatch::error(std::string_view message, std::string_view command) const {
  if (is_homing_command(command) || says_homing_failed(message))
    return fmt::format("homing failed: the printer answered {} with \"{}\"",
                       command.empty() ? std::string_view("a command") : trim(command), trim(message));
  return HomingWatch::message(message);
}

std::string HomingWatch::message(std::string_view text) const {
  if (!homed_ || !says_not_homed(text)) return {};
  return fmt::format("the printer lost its homing (\"{}\"): every move from here on would be refused", trim(text));
}

}  // namespace gcode::serial
