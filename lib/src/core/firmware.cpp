#include "gcode/core/firmware.hpp"

#include <algorithm>

#include "gcode/core/feature.hpp"
#include "gcode/core/line.hpp"

namespace gcode {

std::span<const FirmwareFlavor* const> firmwares() {
  static const FirmwareFlavor* const kAll[] = {&marlin2_firmware(), &marlin1_firmware(), &klipper_firmware(),
                                               &prusa_firmware(), &rrf_firmware()};
  return kAll;
}

std::string firmware_names() {
  std::string names;
  std::span<const FirmwareFlavor* const> all = firmwares();
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (i > 0) names += i + 1 < all.size() ? ", " : " or ";
    names += all[i]->name;
    if (!all[i]->also_named.empty()) {
      names += " (";
      names += all[i]->also_named;
      names += ")";
    }
  }
  return names;
}

bool FirmwareFlavor::lists(std::span<const CommandCode> codes, const Line& line) {
  return std::any_of(codes.begin(), codes.end(), [&](const CommandCode& c) {
    return line.is(c.letter, c.number) && (c.parameter == 0 || line.find(c.parameter) != nullptr);
  });
}

const FirmwareFlavor* find_firmware(std::string_view flavor) {
  for (const FirmwareFlavor* f : firmwares())
    if (same_name(flavor, f->name) || (!f->also_named.empty() && same_name(flavor, f->also_named))) return f;
  return nullptr;
}

const FirmwareFlavor* find_firmware_by_report(std::string_view name) {
  while (!name.empty() && name.front() == ' ') name.remove_prefix(1);
  for (const FirmwareFlavor* f : firmwares())
    if (!f->reports_as.empty() && name.starts_with(f->reports_as)) return f;
  return nullptr;
}

}  // namespace gcode
