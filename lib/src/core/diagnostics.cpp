#include "gcode/core/diagnostics.hpp"

#include <fmt/format.h>

#include <cstdio>

namespace gcode {

Diagnostics::~Diagnostics() {
  if (verbosity_ >= 0 && warnings_ > static_cast<std::uint64_t>(max_warnings_))
    fmt::print(stderr, "{}: {} more warnings not shown\n", tool_, warnings_ - static_cast<std::uint64_t>(max_warnings_));
}

void Diagnostics::warn(std::uint64_t line_number, std::string_view message) {
  ++warnings_;
  if (verbosity_ < 0 || warnings_ > static_cast<std::uint64_t>(max_warnings_)) return;
  if (line_number > 0) {
    fmt::print(stderr, "{}: line {}: warning: {}\n", tool_, line_number, message);
  } else {
    fmt::print(stderr, "{}: warning: {}\n", tool_, message);
  }
}

void Diagnostics::info(std::string_view message) {
  if (verbosity_ >= 1) fmt::print(stderr, "{}: {}\n", tool_, message);
}

void Diagnostics::error(std::string_view message) { fmt::print(stderr, "{}: {}\n", tool_, message); }

void Diagnostics::report(std::string_view message) {
  fmt::print(stderr, "{}: {}\n", tool_, message.substr(0, message.find('\0')));
}

}  // namespace gcode
