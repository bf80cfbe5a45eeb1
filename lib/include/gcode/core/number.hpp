#pragma once
// Reading and writing the decimal numbers of G-code.
//
// Reading: slicers write plain decimals ("12.345", "-.8", "+10", "7800.000");
// those are parsed exactly with integer arithmetic, anything else (exponents,
// very long mantissas) falls back to std::from_chars. No locale, no allocation.
//
// Writing: a value is written with a fixed number of decimals, then trailing
// zeros are dropped ("12.3", "5", "-0.04"), never with an exponent. Formatting
// goes through a scaled integer, which is both fast and free of binary noise.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace gcode {

// Parses the whole of `text` as a number. Accepts a leading '+' or '-', a
// missing leading zero (".5") or missing fraction ("5."), and a C-style
// exponent. Returns false for anything else, including an empty text.
bool parse_number(std::string_view text, double& value);

// Parses "1.5,2,10" (no spaces needed; empty items are an error) into
// finite numbers. Returns false when an item is not a number.
bool parse_number_list(std::string_view text, std::vector<double>& out);

// Digits after the decimal point in a number as written ("0.125" -> 3, "5" -> 0).
int decimals_of(std::string_view number_text);

// Longest text format_number can produce, plus room for a terminator.
inline constexpr std::size_t kMaxNumberChars = 48;

// Writes `value` rounded to `decimals` (0..9) into `out`, trailing zeros and a
// bare point removed, "-0" written as "0". Returns the number of chars written.
// Values beyond +-1e15 are clamped (no G-code axis gets there).
std::size_t format_number(double value, int decimals, char* out);

// `value` in units of 10^-decimals, rounded half away from zero (as
// format_number rounds), clamped as format_number clamps.
std::int64_t to_scaled(double value, int decimals);

// Writes units x 10^-decimals the way format_number writes a value, for
// callers that already hold a scaled integer (exact: nothing to round).
std::size_t format_scaled(std::int64_t units, int decimals, char* out);

// Convenience for tests and messages.
std::string_view number_text(double value, int decimals, char (&buffer)[kMaxNumberChars]);

// The text format_number writes, as a string: the one way messages and
// generated G-code spell a millimetre, a speed or a factor ("0.2", "12").
std::string number_string(double value, int decimals);

}  // namespace gcode
