#include "gcode/objects/label_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>

namespace gcode {

std::vector<std::string> klipper_names(const ObjectTable& table) {
  std::vector<std::string> names;
  auto clean = [](std::string s) {
    for (char& c : s)
      if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.')) c = '_';
    return s;
  };
  for (const PlateObject& o : table.objects) names.push_back(clean(o.name));
  const std::vector<std::string> plain = names;
  for (std::size_t i = 0; i < names.size(); ++i)
    if (std::count(plain.begin(), plain.end(), plain[i]) > 1) names[i] = clean(table.objects[i].name + "_id_" + table.objects[i].id);
  return names;
}

LabelWriter::LabelWriter(const ObjectTable& table, FirmwareLabels kind)
    : table_(table), kind_(kind), names_(klipper_names(table)), named_(table.objects.size(), false) {}

void LabelWriter::begin(int object, Emitter& out) {
  if (object < 0 || static_cast<std::size_t>(object) >= names_.size()) return;
  const auto i = static_cast<std::size_t>(object);
  if (kind_ == FirmwareLabels::Klipper) {
    out.insert("EXCLUDE_OBJECT_START NAME=" + names_[i]);
  } else if (!named_[i]) {
    // RepRapFirmware reads the quoted name; Marlin skips it.
    std::string name = table_.objects[i].name;
    std::replace(name.begin(), name.end(), '"', '\'');
    out.insert(fmt::format("M486 S{} A\"{}\"", i, name));
    named_[i] = true;
  } else {
    out.insert(fmt::format("M486 S{}", i));
  }
}

void LabelWriter::end(int object, Emitter& out) {
  if (object < 0 || static_cast<std::size_t>(object) >= names_.size()) return;
  out.insert(kind_ == FirmwareLabels::Klipper ? "EXCLUDE_OBJECT_END NAME=" + names_[static_cast<std::size_t>(object)]
                                               : std::string("M486 S-1"));
}

void LabelWriter::layer(const LayerInfo& info, const MachineState& before, Emitter& out) {
  if (!declared_) {
    declared_ = true;
    if (kind_ == FirmwareLabels::Marlin) out.insert(fmt::format("M486 T{}", table_.objects.size()));
    for (std::size_t i = 0; kind_ == FirmwareLabels::Klipper && i < table_.objects.size(); ++i) {
      const PlateObject& o = table_.objects[i];
      std::string polygon;
      auto to = std::back_inserter(polygon);
      for (const Point2& p : o.outline) fmt::format_to(to, "{}[{:.3f},{:.3f}]", polygon.empty() ? "" : ",", p.x, p.y);
      const Point2 c = o.box.empty() ? Point2{} : o.box.centre();
      out.insert(fmt::format("EXCLUDE_OBJECT_DEFINE NAME={} CENTER={:.3f},{:.3f} POLYGON=[{}]", names_[i], c.x, c.y, polygon));
    }
  }
  const int was = tracker_.current();
  tracker_.layer();
  if (tracker_.current() != was) end(was, out);
  out.layer(info, before);
}

void LabelWriter::line(const TrackedLine& t, Emitter& out) {
  const int was = tracker_.current();
  const int now = tracker_.line(t.line);
  if (now == was) {
    out.pass(t);
    return;
  }
  end(was, out);
  out.pass(t);
  begin(now, out);
}

void LabelWriter::finish(Emitter& out) { end(tracker_.current(), out); }

}  // namespace gcode
