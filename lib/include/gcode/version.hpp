#pragma once
namespace gcode {
inline constexpr const char* kVersion = "0.1.0";
}  // namespace gcode
