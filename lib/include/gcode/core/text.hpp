#pragma once
// Small text helpers for what users type (control commands, pause methods,
// G-code given as text): ASCII case-insensitive comparison, and lines of a
// text block.
#include <string>
#include <string_view>
#include <vector>

namespace gcode {

bool iequals(std::string_view a, std::string_view b);
// `s` without the white space (C's isspace: blank, tab, CR, LF, VT, FF) at
// either end.
std::string_view trim(std::string_view s);
// The lines of `text` ('\n' or "\r\n" between them), empty ones left out.
std::vector<std::string> split_lines(std::string_view text);

}  // namespace gcode
