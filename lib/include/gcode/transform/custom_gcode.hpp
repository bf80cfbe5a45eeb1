#pragma once
// G-code the user adds to a block (--before, --after, custom:... of a pause;
// gc-send's `gcode` command): the name of a file to read, or the text itself
// with "\n" (backslash n) between lines, as a shell makes it easy to type.
#include <string>
#include <string_view>

namespace gcode {

// A readable regular file is read whole; anything else is text with "\n"
// turned into newlines. Throws std::runtime_error when a file cannot be read.
std::string load_custom_gcode(std::string_view value);

}  // namespace gcode
