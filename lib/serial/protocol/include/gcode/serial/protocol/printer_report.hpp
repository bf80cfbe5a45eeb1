#pragma once
// What a printer says about where it is, read from its answers: after a
// fault, gc-send asks before it trusts its journal (journal.hpp).
//
//  * M114: "X:10.00 Y:20.00 Z:0.30 E:12.00 Count X:800 Y:1600 Z:120" (Marlin,
//    Prusa), "X:10.000 Y:20.000 Z:0.300 E:12.000" (Klipper), RepRapFirmware
//    the same with "Count"/"Machine"/"User" sections after it. The first
//    X/Y/Z/E group is the logical position (what the G-code said); the
//    step counts after "Count" are not positions and are ignored.
//  * The line the firmware expects next: a line sent with a deliberately
//    wrong number is refused with "Error:Line Number is not Last Line
//    Number+1, Last Line: 1234" (any of Marlin's line errors names the last
//    line it took), then "Resend: 1235".
#include <array>
#include <optional>
#include <string_view>

namespace gcode::serial {

struct PositionReport {
  std::array<double, 4> axis{};     // X Y Z E, mm, as the printer reports them
  std::array<bool, 4> present{};    // which of them the report named
};

// Reads an M114 answer (one line, "ok " prefix allowed); nullopt when the
// line is not one (it has no X:, Y: and Z: before any "Count").
std::optional<PositionReport> parse_position_report(std::string_view line);

// Whether the printer stands where it should: the first of X, Y, Z (0, 1,
// 2) at which `report` is more than `tolerance` mm from `expected`; -1 when
// none is. The one check of "where is the printer" after a fault, for the
// sender's reconnect and gc-send --resume's plan alike.
int axis_off(const PositionReport& report, const std::array<double, 3>& expected, double tolerance);

// The "Last Line: n" of a Marlin line error; nullopt when it names none.
std::optional<long long> last_line_of(std::string_view error);

}  // namespace gcode::serial
