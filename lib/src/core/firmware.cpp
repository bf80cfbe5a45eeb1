#include "gcode/core/firmware.hpp"

#include <algorithm>
#include <initializer_list>

#include "gcode/core/feature.hpp"
#include "gcode/core/line.hpp"

namespace gcode {

bool FirmwareFlavor::lists(std::span<const CommandCode> codes, const Line& line) {
  return std::any_of(codes.begin(), codes.end(), [&](const CommandCode& c) { return line.is(c.letter, c.number); });
}

const FirmwareFlavor* find_firmware(std::string_view flavor) {
  for (const FirmwareFlavor* f : {&marlin2_firmware(), &marlin1_firmware()})
    if (same_name(flavor, f->name)) return f;
  return nullptr;
}

}  // namespace gcode
