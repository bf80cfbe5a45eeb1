#include "gcode/transform/carried_settings.hpp"

#include <algorithm>
#include <cctype>

#include "gcode/core/line_builder.hpp"
#include "gcode/core/text.hpp"

namespace gcode {

namespace {

// The value of a word that has one, as an exact decimal.
bool word_value(const Line& line, char letter, Fixed& out) {
  const Word* w = line.find(letter);
  const bool has = w != nullptr && w->has_value;
  if (has) out = w->fixed();
  return has;
}

int word_int(const Line& line, char letter, int fallback) {
  return static_cast<int>(line.value_or(letter, fallback));
}

CarriedSettings::Kind kind_of(HeaterFanLine::Kind k) {
  switch (k) {
    case HeaterFanLine::Kind::Bed: return CarriedSettings::Kind::Bed;
    case HeaterFanLine::Kind::Chamber: return CarriedSettings::Kind::Chamber;
    case HeaterFanLine::Kind::Hotend: return CarriedSettings::Kind::Hotend;
    case HeaterFanLine::Kind::Fan: return CarriedSettings::Kind::Fan;
  }
  return CarriedSettings::Kind::Hotend;
}

// Klipper names the extruder in a parameter ("EXTRUDER=extruder1"); the
// slot is the command plus that parameter, the value the whole text.
std::string klipper_slot(std::string_view argument) {
  std::string slot;
  std::size_t pos = 0;
  while (pos < argument.size()) {
    std::size_t end = argument.find(' ', pos);
    if (end == std::string_view::npos) end = argument.size();
    std::string_view item = argument.substr(pos, end - pos);
    if (item.size() > 9 && iequals(item.substr(0, 9), "EXTRUDER=")) slot.assign(item);
    pos = end + 1;
  }
  return slot;
}

int kind_rank(CarriedSettings::Kind k) { return static_cast<int>(k); }

// Klipper's SET_PRESSURE_ADVANCE is compared by its text (it may set two values).
bool by_text(const CarriedSettings::Setting& s) { return s.command.rfind("SET_PRESSURE_ADVANCE", 0) == 0; }

bool same_value(const CarriedSettings::Setting& a, const CarriedSettings::Setting& b) {
  return by_text(a) ? a.text == b.text : a.value == b.value;
}

}  // namespace

const CarriedSettings::Setting* CarriedSettings::find(Kind kind, int index, std::string_view command) const {
  for (const Setting& s : settings_)
    if (s.kind == kind && s.index == index && (command.empty() || s.command == command)) return &s;
  return nullptr;
}

void CarriedSettings::set(Setting s) {
  for (Setting& old : settings_) {
    if (old.kind == s.kind && old.index == s.index && old.command == s.command) {
      old.value = s.value;
      old.text = std::move(s.text);
      return;
    }
  }
  // Kept in the order lines_from writes them, so equal sets compare equal.
  auto at = std::find_if(settings_.begin(), settings_.end(), [&](const Setting& o) {
    if (kind_rank(o.kind) != kind_rank(s.kind)) return kind_rank(o.kind) > kind_rank(s.kind);
    if (o.index != s.index) return o.index > s.index;
    return o.command > s.command;
  });
  settings_.insert(at, std::move(s));
}

bool CarriedSettings::observe(const Line& line, int tool) {
  if (!may_set(line)) return false;
  Setting s;
  Fixed v;
  if (line.kind == CommandKind::Extended) {
    if (!iequals(line.command, "SET_PRESSURE_ADVANCE")) return false;
    s.kind = Kind::Advance;
    s.command = "SET_PRESSURE_ADVANCE " + klipper_slot(line.argument);
    s.text.assign(line.code());
    set(std::move(s));
    return true;
  }
  s.text.assign(line.code());
  // Heaters and fans are read as the machine state reads them.
  HeaterFanLine h;
  if (read_heater_fan(line, tool, h)) {
    s.kind = kind_of(h.kind);
    s.index = h.index;
    s.value = h.value;
    set(std::move(s));
    return true;
  }
  if (line.letter != 'M') return false;
  switch (line.number) {
    case 221:
      if (!word_value(line, 'S', v)) return false;  // a bare M221 reports
      s.kind = Kind::Flow;
      s.index = word_int(line, 'T', tool);
      break;
    case 900:
      if (!word_value(line, 'K', v)) return false;
      s.kind = Kind::Advance;
      s.command = "M900";
      s.index = word_int(line, 'T', tool);
      break;
    case 572:
      if (!word_value(line, 'S', v)) return false;
      s.kind = Kind::Advance;
      s.command = "M572";
      s.index = word_int(line, 'D', 0);
      break;
    default:
      return false;
  }
  s.value = v;
  set(std::move(s));
  return true;
}

std::vector<std::string> CarriedSettings::lines_from(const CarriedSettings& from, int tool) const {
  std::vector<std::string> lines;
  LineBuilder b;
  for (const Setting& s : settings_) {
    const Setting* old = from.find(s.kind, s.index, s.command);
    if (old != nullptr && same_value(*old, s)) continue;
    bool rises = old == nullptr || s.value > old->value;
    switch (s.kind) {
      case Kind::Bed:
      case Kind::Chamber: {
        const bool bed = s.kind == Kind::Bed;
        b.start(rises ? (bed ? "M190" : "M191") : (bed ? "M140" : "M141")).fixed('S', s.value);
        lines.emplace_back(b.view());
        break;
      }
      case Kind::Hotend:
        if (s.text.rfind("G10", 0) == 0 || s.text.rfind("g10", 0) == 0) {
          lines.push_back(s.text);  // RepRapFirmware sets standby and active together
          break;
        }
        b.start(rises ? "M109" : "M104");
        if (s.index != tool) b.word('T', s.index, 0);
        b.fixed('S', s.value);
        lines.emplace_back(b.view());
        break;
      default:
        lines.push_back(s.text);
        break;
    }
  }
  return lines;
}

bool operator==(const CarriedSettings& a, const CarriedSettings& b) {
  if (a.settings_.size() != b.settings_.size()) return false;
  for (std::size_t i = 0; i < a.settings_.size(); ++i) {
    const auto& x = a.settings_[i];
    const auto& y = b.settings_[i];
    if (x.kind != y.kind || x.index != y.index || x.command != y.command || !same_value(x, y)) return false;
  }
  return true;
}

}  // namespace gcode
