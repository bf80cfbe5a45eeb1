#include "gcode/serial/sim/virtual_printer_options.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "gcode/core/firmware.hpp"

namespace gcode::serial {

namespace {

double parse_value(std::string_view key, std::string_view value) {
  double v = 0;
  auto res = std::from_chars(value.data(), value.data() + value.size(), v);
  if (res.ec != std::errc() || res.ptr != value.data() + value.size() || !std::isfinite(v) || v < 0)
    throw std::invalid_argument(fmt::format("virtual printer option {}: '{}' is not a number >= 0", key, value));
  return v;
}

bool parse_flag(std::string_view key, std::string_view value) {
  if (value.empty() || value == "1" || value == "on" || value == "yes" || value == "true") return true;
  if (value == "0" || value == "off" || value == "no" || value == "false") return false;
  throw std::invalid_argument(fmt::format("virtual printer option {}: '{}' is not on/off", key, value));
}

double probability(std::string_view key, std::string_view value) {
  double p = parse_value(key, value);
  if (p > 1) throw std::invalid_argument(fmt::format("virtual printer option {}: {} is not a probability", key, value));
  return p;
}

}  // namespace

void parse_virtual_options(std::string_view text, VirtualPrinterConfig& c) {
  while (!text.empty()) {
    std::size_t comma = text.find(',');
    std::string_view item = text.substr(0, comma);
    text = comma == std::string_view::npos ? std::string_view() : text.substr(comma + 1);
    if (item.empty()) continue;
    if (item.find('@') != std::string_view::npos) {
      c.scheduled.push_back(parse_scheduled_fault(item));
      continue;
    }
    std::size_t eq = item.find('=');
    std::string_view key = item.substr(0, eq);
    std::string_view value = eq == std::string_view::npos ? std::string_view() : item.substr(eq + 1);
    auto count = [&](double lo) {
      double v = parse_value(key, value);
      if (v < lo || v != std::floor(v))
        throw std::invalid_argument(fmt::format("virtual printer option {}: '{}' must be a whole number >= {}", key, value, lo));
      return v;
    };
    if (key == "firmware") {
      if (find_firmware(value) == nullptr)
        throw std::invalid_argument(
            fmt::format("virtual printer option firmware: '{}' is not {}", value, firmware_names()));
      c.firmware = std::string(value);
    } else if (key == "user-seconds") {
      c.user_seconds = parse_value(key, value);
    } else if (key == "resend-ok") {
      c.resend_ok = parse_flag(key, value);
    } else if (key == "idle-wait") {
      c.idle_wait = parse_value(key, value);
    } else if (key == "baud") {
      c.baud = count(50);
    } else if (key == "queue") {
      c.queue = static_cast<int>(count(1));
    } else if (key == "rx") {
      c.rx_buffer = static_cast<int>(count(16));
    } else if (key == "write-timeout") {
      c.write_timeout = parse_value(key, value);
    } else if (key == "scripted-errors") {
      c.scripted_errors = parse_flag(key, value);
    } else if (key == "octoprint" && parse_flag(key, value)) {
      // OctoPrint's virtual printer with its default settings.
      c.rx_buffer = 64;
      c.write_timeout = 10;
      c.scripted_errors = true;
      c.instant_moves = true;
    } else if (key == "octoprint") {
    } else if (key == "max-line") {
      c.max_line = static_cast<int>(count(16));
    } else if (key == "planner") {
      c.planner = static_cast<int>(count(1));
    } else if (key == "time-scale") {
      c.time_scale = parse_value(key, value);
      if (c.time_scale <= 0) throw std::invalid_argument("virtual printer option time-scale must be > 0");
    } else if (key == "speed-factor") {
      c.speed_factor = parse_value(key, value);
      if (c.speed_factor <= 0) throw std::invalid_argument("virtual printer option speed-factor must be > 0");
    } else if (key == "advanced-ok") {
      c.advanced_ok = parse_flag(key, value);
    } else if (key == "instant-moves") {
      c.instant_moves = parse_flag(key, value);
    } else if (key == "simulated-clock") {
      c.simulated_clock = value.empty() ? VirtualPrinterConfig::kHostLatency : parse_value(key, value);
    } else if (key == "report-link") {
      c.report_link = parse_flag(key, value);
    } else if (key == "heat-rate") {
      c.heat_rate = std::max(0.01, parse_value(key, value));
    } else if (key == "corrupt") {
      c.corrupt = probability(key, value);
    } else if (key == "drop-ok") {
      c.drop_ok = probability(key, value);
    } else if (key == "resend") {
      c.resend = probability(key, value);
    } else if (key == "garbage") {
      c.garbage = probability(key, value);
    } else if (key == "busy") {
      c.busy = probability(key, value);
    } else if (key == "silent-after") {
      c.silent_after = static_cast<long long>(count(0));
    } else if (key == "halt-after") {
      c.halt_after = static_cast<long long>(count(0));
    } else if (key == "disconnect-after") {
      c.disconnect_after = static_cast<long long>(count(0));
    } else if (key == "home-fails") {
      c.home_fails = parse_flag(key, value);
    } else if (key == "unhome-after") {
      c.unhome_after = static_cast<long long>(count(0));
    } else if (key == "log") {
      c.log_path = std::string(value);
    } else if (key == "greeting") {
      c.greeting = parse_greeting_form(value);
    } else if (key == "seed") {
      c.seed = static_cast<std::uint32_t>(count(0));
    } else {
      throw std::invalid_argument(fmt::format("unknown virtual printer option '{}'", key));
    }
  }
}

}  // namespace gcode::serial
