#include "gcode/serial/protocol/printer_report.hpp"

#include <cctype>
#include <charconv>
#include <cmath>

namespace gcode::serial {

namespace {

int axis_index(char c) {
  switch (std::toupper(static_cast<unsigned char>(c))) {
    case 'X': return 0;
    case 'Y': return 1;
    case 'Z': return 2;
    case 'E': return 3;
    default: return -1;
  }
}

bool read_number(std::string_view text, std::size_t& pos, double& out) {
  const char* begin = text.data() + pos;
  if (pos < text.size() && text[pos] == '+') ++begin;
  auto [end, ec] = std::from_chars(begin, text.data() + text.size(), out);
  if (ec != std::errc()) return false;
  pos = static_cast<std::size_t>(end - text.data());
  return true;
}

}  // namespace

std::optional<PositionReport> parse_position_report(std::string_view line) {
  if (line.size() >= 3 && (line.substr(0, 3) == "ok " || line.substr(0, 3) == "OK ")) line.remove_prefix(3);
  std::size_t count = line.find("Count");
  if (count != std::string_view::npos) line = line.substr(0, count);
  PositionReport r;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    int a = axis_index(line[i]);
    bool starts_word = i == 0 || line[i - 1] == ' ';
    if (a < 0 || !starts_word || line[i + 1] != ':') continue;
    std::size_t pos = i + 2;
    double v = 0;
    if (!read_number(line, pos, v)) return std::nullopt;
    if (!r.present[static_cast<std::size_t>(a)]) {
      r.axis[static_cast<std::size_t>(a)] = v;
      r.present[static_cast<std::size_t>(a)] = true;
    }
    i = pos - 1;
  }
  if (!r.present[0] || !r.present[1] || !r.present[2]) return std::nullopt;
  return r;
}

std::optional<long long> last_line_of(std::string_view error) {
  constexpr std::string_view kKey = "Last Line:";
  std::size_t at = error.find(kKey);
  if (at == std::string_view::npos) return std::nullopt;
  std::size_t pos = at + kKey.size();
  while (pos < error.size() && error[pos] == ' ') ++pos;
  long long n = 0;
  auto [end, ec] = std::from_chars(error.data() + pos, error.data() + error.size(), n);
  if (ec != std::errc() || end == error.data() + pos) return std::nullopt;
  return n;
}

int axis_off(const PositionReport& report, const std::array<double, 3>& expected, double tolerance) {
  for (std::size_t a = 0; a < 3; ++a)
    if (report.present[a] && std::fabs(report.axis[a] - expected[a]) > tolerance) return static_cast<int>(a);
  return -1;
}

}  // namespace gcode::serial
