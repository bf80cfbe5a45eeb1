#include "gcode/core/firmware.hpp"

#include <algorithm>
#include <array>

#include "gcode/core/feature.hpp"
#include "gcode/core/line.hpp"

namespace gcode {

namespace {

const std::array<const FirmwareFlavor*, 5>& described() {
  static const std::array<const FirmwareFlavor*, 5> all = {&marlin2_firmware(), &marlin1_firmware(),
                                                           &klipper_firmware(), &prusa_firmware(), &rrf_firmware()};
  return all;
}

}  // namespace

bool FirmwareFlavor::lists(std::span<const CommandCode> codes, const Line& line) {
  return std::any_of(codes.begin(), codes.end(), [&](const CommandCode& c) {
    return line.is(c.letter, c.number) && (c.parameter == 0 || line.find(c.parameter) != nullptr);
  });
}

const FirmwareFlavor* find_firmware(std::string_view flavor) {
  if (same_name(flavor, "rrf")) return &rrf_firmware();
  for (const FirmwareFlavor* f : described())
    if (same_name(flavor, f->name)) return f;
  return nullptr;
}

const FirmwareFlavor* find_firmware_by_report(std::string_view name) {
  while (!name.empty() && name.front() == ' ') name.remove_prefix(1);
  for (const FirmwareFlavor* f : described())
    if (!f->reports_as.empty() && name.starts_with(f->reports_as)) return f;
  return nullptr;
}

}  // namespace gcode
