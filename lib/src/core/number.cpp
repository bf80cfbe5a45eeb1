#include "gcode/core/number.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace gcode {

namespace {

constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                             1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                             1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
constexpr std::int64_t kPow10Int[] = {1,         10,         100,         1000,
                                      10000,     100000,     1000000,     10000000,
                                      100000000, 1000000000, 10000000000, 100000000000};

bool parse_slow(std::string_view text, double& value) {
  const char* p = text.data();
  const char* end = p + text.size();
  if (p != end && *p == '+') ++p;
  // from_chars does not take "5." or ".5" with a sign issue; normalise those.
  auto [ptr, ec] = std::from_chars(p, end, value, std::chars_format::general);
  if (ec == std::errc::result_out_of_range) {
    value = HUGE_VAL;
    return false;
  }
  return ec == std::errc() && ptr == end;
}

}  // namespace

bool parse_number(std::string_view text, double& value) {
  const char* p = text.data();
  const char* end = p + text.size();
  bool negative = false;
  if (p != end && (*p == '-' || *p == '+')) {
    negative = *p == '-';
    ++p;
  }
  std::uint64_t mantissa = 0;
  int digits = 0;
  int fraction_digits = 0;
  bool seen_point = false;
  for (; p != end; ++p) {
    char c = *p;
    if (c >= '0' && c <= '9') {
      mantissa = mantissa * 10 + static_cast<unsigned>(c - '0');
      ++digits;
      if (seen_point) ++fraction_digits;
    } else if (c == '.' && !seen_point) {
      seen_point = true;
    } else {
      break;
    }
  }
  if (digits == 0) return false;
  if (p == end && digits <= 15 && fraction_digits <= 22) {
    // Both operands are exact doubles, so one IEEE division rounds correctly.
    double v = static_cast<double>(mantissa) / kPow10[fraction_digits];
    value = negative ? -v : v;
    return true;
  }
  if (p != end && *p != 'e' && *p != 'E') return false;
  // Exponent or a very long mantissa: let the standard library decide.
  if (text.size() > 1 && text[0] == '+') text.remove_prefix(1);
  std::string_view rest = text;
  if (!rest.empty() && rest[0] == '.') {
    char buffer[512];
    if (rest.size() + 1 >= sizeof buffer) return false;
    buffer[0] = '0';
    std::memcpy(buffer + 1, rest.data(), rest.size());
    return parse_slow(std::string_view(buffer, rest.size() + 1), value);
  }
  return parse_slow(rest, value);
}

bool parse_number_list(std::string_view text, std::vector<double>& out) {
  out.clear();
  for (;;) {
    std::size_t comma = text.find(',');
    std::string_view item = text.substr(0, comma);
    while (!item.empty() && item.front() == ' ') item.remove_prefix(1);
    while (!item.empty() && item.back() == ' ') item.remove_suffix(1);
    double v = 0;
    if (!parse_number(item, v) || !std::isfinite(v)) return false;
    out.push_back(v);
    if (comma == std::string_view::npos) return true;
    text.remove_prefix(comma + 1);
  }
}

int decimals_of(std::string_view number_text) {
  // A plain loop: numbers are a few characters, and find() costs a memchr
  // call per word (gc-layers asks for every word of every line).
  const char* p = number_text.data();
  const char* end = p + number_text.size();
  while (p != end && *p != '.') ++p;
  if (p == end) return 0;
  const char* first = ++p;
  while (p != end && *p >= '0' && *p <= '9') ++p;
  return static_cast<int>(p - first);
}

std::int64_t to_scaled(double value, int decimals) {
  if (decimals < 0) decimals = 0;
  if (decimals > 9) decimals = 9;
  if (!(value == value)) value = 0;  // NaN never reaches a printer as text
  if (value > 1e15) value = 1e15;
  if (value < -1e15) value = -1e15;
  double x = value * kPow10[decimals];
  if (x > 9e18) x = 9e18;  // 1e15 at 9 decimals would not fit an int64
  if (x < -9e18) x = -9e18;
  // llround without the libm call (a hot spot when tools write millions of
  // numbers): truncate, then x - t is exact below 2^52, so the half-away-from-
  // zero rule is applied to the true remainder.
  auto scaled = static_cast<std::int64_t>(x);
  double rest = x - static_cast<double>(scaled);
  if (rest >= 0.5) {
    ++scaled;
  } else if (rest <= -0.5) {
    --scaled;
  }
  return scaled;
}

std::size_t format_number(double value, int decimals, char* out) {
  return format_scaled(to_scaled(value, decimals), decimals, out);
}

namespace {

// One instance per precision, so every division is by a constant (a multiply).
template <int D>
char* write_scaled(std::uint64_t magnitude, char* p) {
  constexpr auto unit = static_cast<std::uint64_t>(kPow10Int[D]);
  std::uint64_t whole = magnitude / unit;
  std::uint64_t fraction = magnitude % unit;
  p = std::to_chars(p, p + 24, whole).ptr;
  if constexpr (D > 0) {
    if (fraction != 0) {
      *p++ = '.';
      // All D digits zero-padded, then the trailing zeros cut off.
      for (int i = D - 1; i >= 0; --i) {
        p[i] = static_cast<char>('0' + fraction % 10);
        fraction /= 10;
      }
      int len = D;
      while (p[len - 1] == '0') --len;
      p += len;
    }
  }
  return p;
}

}  // namespace

std::size_t format_scaled(std::int64_t units, int decimals, char* out) {
  char* p = out;
  std::uint64_t magnitude = units < 0 ? 0 - static_cast<std::uint64_t>(units) : static_cast<std::uint64_t>(units);
  if (units < 0) *p++ = '-';
  switch (decimals <= 0 ? 0 : decimals >= 9 ? 9 : decimals) {
    case 0: p = write_scaled<0>(magnitude, p); break;
    case 1: p = write_scaled<1>(magnitude, p); break;
    case 2: p = write_scaled<2>(magnitude, p); break;
    case 3: p = write_scaled<3>(magnitude, p); break;
    case 4: p = write_scaled<4>(magnitude, p); break;
    case 5: p = write_scaled<5>(magnitude, p); break;
    case 6: p = write_scaled<6>(magnitude, p); break;
    case 7: p = write_scaled<7>(magnitude, p); break;
    case 8: p = write_scaled<8>(magnitude, p); break;
    default: p = write_scaled<9>(magnitude, p); break;
  }
  return static_cast<std::size_t>(p - out);
}

std::string_view number_text(double value, int decimals, char (&buffer)[kMaxNumberChars]) {
  return {buffer, format_number(value, decimals, static_cast<char*>(buffer))};
}

std::string number_string(double value, int decimals) {
  char buffer[kMaxNumberChars];
  return {buffer, format_number(value, decimals, buffer)};
}

}  // namespace gcode
