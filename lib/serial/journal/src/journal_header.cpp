#include "gcode/serial/journal/journal_header.hpp"

#include <fmt/format.h>

namespace gcode::serial {

JournalFields journal_header(const InputIdentity& input, std::string_view port) {
  JournalFields h;
  h.set("input", input.path);
  h.set("regular", input.regular ? "1" : "0");
  h.set("size", std::to_string(input.size));
  h.set("mtime", std::to_string(input.mtime_ns));
  h.set("port", std::string(port));
  return h;
}

std::string input_mismatch(const JournalFields& header, const InputIdentity& now) {
  std::string was = header.get("input");
  bool was_regular = header.get("regular") == "1";
  if (was_regular != now.regular)
    return was_regular ? fmt::format("the journal is of the file {}, not a stream", was)
                       : fmt::format("the journal is of a stream ({}), not a file", was);
  if (!now.regular) return std::string();
  if (was != now.path) return fmt::format("the journal is of {}, not {}", was, now.path);
  if (header.get("size") != std::to_string(now.size))
    return fmt::format("{} changed since the print: {} bytes then, {} now", now.path, header.get("size"), now.size);
  if (header.get("mtime") != std::to_string(now.mtime_ns))
    return fmt::format("{} was modified since the print (same size, another time)", now.path);
  return std::string();
}

}  // namespace gcode::serial
