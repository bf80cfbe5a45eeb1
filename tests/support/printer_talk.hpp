#pragma once
// Shared by the virtual printer's unit tests: talking to the model directly,
// without a link or an event loop.
#include <string>
#include <string_view>
#include <vector>

#include "gcode/serial/protocol/protocol.hpp"
#include "gcode/serial/sim/virtual_printer.hpp"

namespace gctest {

// Runs the model to `until` and returns the lines it sent by then.
inline std::vector<std::string> answers(gcode::serial::VirtualPrinter& p, double until) {
  p.advance(until);
  std::string_view out = p.transmitted(until);
  std::vector<std::string> lines;
  std::size_t pos = 0;
  for (std::size_t nl; (nl = out.find('\n', pos)) != std::string_view::npos; pos = nl + 1)
    lines.emplace_back(out.substr(pos, nl - pos));
  p.take(pos);
  return lines;
}

// "N<n> <cmd>*<checksum>\n", as a host sends it.
inline std::string numbered(long long n, std::string_view cmd) {
  std::string s;
  gcode::serial::append_numbered_line(s, n, cmd);
  return s;
}

}  // namespace gctest
