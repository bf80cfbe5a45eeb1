#pragma once
// {name} placeholders in text the user gives: a pause message "Paused at
// layer {layer}, Z {z}", custom G-code, an output pattern "layer-{}.svg".
// One implementation for every tool: each {name} with a value is replaced
// (every occurrence), unknown names are left as they are.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace gcode {

using Placeholders = std::vector<std::pair<std::string_view, std::string>>;

// `values`: name (without braces; "" for "{}") and its text.
std::string expand_placeholders(std::string_view text, const Placeholders& values);
// Whether `text` holds "{name}".
bool has_placeholder(std::string_view text, std::string_view name);

}  // namespace gcode
