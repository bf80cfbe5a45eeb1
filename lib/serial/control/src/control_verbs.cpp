// Reading a line by the table of control verbs, and the table's list for
// --help (control_verbs.hpp).
#include "gcode/serial/control/control_verbs.hpp"

#include <optional>

#include <fmt/format.h>

#include "gcode/core/text.hpp"

namespace gcode::serial {

namespace {

// The rest of `line` after the verb's words, or nullopt when they do not
// begin it.
std::optional<std::string_view> after_words(std::string_view line, std::string_view words) {
  while (!words.empty()) {
    std::size_t w = words.find(' ');
    std::size_t l = line.find_first_of(" \t");
    if (!iequals(line.substr(0, l), words.substr(0, w))) return std::nullopt;
    line = l == std::string_view::npos ? std::string_view() : trim(line.substr(l));
    words = w == std::string_view::npos ? std::string_view() : words.substr(w + 1);
  }
  return line;
}

}  // namespace

bool ControlCommand::is(std::string_view name) const { return verb != nullptr && verb->name == name; }

ControlCommand parse_control_command(std::string_view line) {
  ControlCommand c;
  line = trim(line);
  std::string_view rest;
  for (const ControlVerb& v : control_verbs()) {
    std::optional<std::string_view> after = after_words(line, v.name);
    if (after && (c.verb == nullptr || v.name.size() > c.verb->name.size())) {
      c.verb = &v;
      rest = *after;
    }
  }
  auto unknown = [&](std::string why) {
    c.verb = nullptr;
    c.argument = std::move(why);
    return c;
  };
  if (c.verb == nullptr) return unknown(fmt::format("unknown command '{}'", line));
  const ControlVerb& v = *c.verb;
  if (v.argument.empty() && !rest.empty()) return unknown(fmt::format("'{}' takes no argument: '{}'", v.name, line));
  if (!v.argument.empty() && rest.empty()) return unknown(fmt::format("'{}' needs an argument", v.name));
  c.argument = std::string(rest);
  if (v.read != nullptr) {
    std::string why = v.read(rest, c);
    if (!why.empty()) return unknown(std::move(why));
  }
  return c;
}

std::string ControlVerb::usage() const {
  return argument.empty() ? std::string(name) : fmt::format("{} {}", name, argument);
}

const ControlVerb* find_control_verb(std::string_view name) {
  for (const ControlVerb& v : control_verbs())
    if (v.name == name) return &v;
  return nullptr;
}

std::string control_verbs_help() {
  std::string text;
  for (const ControlVerb& v : control_verbs()) text += fmt::format("  {:<12} {}\n", v.usage(), v.help);
  return text;
}

}  // namespace gcode::serial
