#include "gcode/core/print_area.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "gcode/core/file_ends.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/core/number.hpp"
#include "gcode/core/text.hpp"

namespace gcode {

namespace {

// The head holds Cura's and Griffin's header; the tail holds PrusaSlicer's
// config block (about 60 KB; custom G-code in it can make it longer).
constexpr std::size_t kHeadBytes = 64u << 10;
constexpr std::size_t kTailBytes = 1u << 20;
constexpr std::size_t kMaxCuraSettings = 1u << 20;
// Unset Cura header values come out as +-2.14748e+06 from the bare CLI.
constexpr double kSane = 1e5;
// A retraction longer than this is a typo or a filament unload, not a retraction.
constexpr double kMaxRetract = 50;

bool number_of(std::string_view text, double& v) { return parse_number(trim(text), v) && std::fabs(v) < kSane; }

// "key = value" after the ';', or nothing.
bool key_value(std::string_view c, std::string_view key, std::string_view& value) {
  c = trim(c);
  if (c.size() <= key.size() || c.substr(0, key.size()) != key) return false;
  std::string_view rest = trim(c.substr(key.size()));
  if (rest.empty() || rest.front() != '=') return false;
  value = trim(rest.substr(1));
  return true;
}

// "0x0,250x0,250x210,0x210" -> the bounding box of the polygon.
bool polygon_box(std::string_view text, Box2& box) {
  bool any = false;
  while (!text.empty()) {
    std::size_t comma = text.find(',');
    std::string_view point = trim(text.substr(0, comma));
    std::size_t x = point.find('x');
    double px = 0, py = 0;
    if (x == std::string_view::npos || !number_of(point.substr(0, x), px) || !number_of(point.substr(x + 1), py))
      return false;
    if (!any) {
      box = Box2{px, py, px, py};
      any = true;
    } else {
      box.min_x = std::min(box.min_x, px);
      box.min_y = std::min(box.min_y, py);
      box.max_x = std::max(box.max_x, px);
      box.max_y = std::max(box.max_y, py);
    }
    if (comma == std::string_view::npos) break;
    text.remove_prefix(comma + 1);
  }
  return any && box.max_x > box.min_x && box.max_y > box.min_y;
}

// Cura's settings are an escaped INI text: "machine_width = 220\\n".
bool cura_setting(std::string_view all, std::string_view key, double& v) {
  std::string pattern = std::string(key) + " = ";
  std::size_t at = all.find(pattern);
  if (at == std::string_view::npos) return false;
  std::string_view rest = all.substr(at + pattern.size());
  std::size_t end = 0;
  while (end < rest.size() && (std::isdigit(static_cast<unsigned char>(rest[end])) || rest[end] == '.' || rest[end] == '-'))
    ++end;
  return end > 0 && number_of(rest.substr(0, end), v);
}

// Filament is 1.75 or 2.85 mm (3 mm nominal); anything outside this is not a diameter.
bool sane_diameter(double d) { return d > 0.5 && d < 5; }

// The first number of a list ("1.75,1.75", "1.75|2.85"), a unit after it allowed ("1.75mm").
bool first_number(std::string_view text, double& v) {
  text = trim(text);
  std::size_t end = text.find_first_of(",|; \t");
  std::string_view item = text.substr(0, end);
  if (item.size() > 2 && (item.substr(item.size() - 2) == "mm" || item.substr(item.size() - 2) == "MM"))
    item.remove_suffix(2);
  return number_of(item, v);
}

bool starts_with_nocase(std::string_view text, std::string_view prefix) {
  if (text.size() < prefix.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(text[i])) != std::tolower(static_cast<unsigned char>(prefix[i])))
      return false;
  return true;
}

// ";Filament Diameter: 2.85", ";Filament diameter: 1.75mm", ";Filament Diameter #0: 1.75".
bool filament_diameter_comment(std::string_view c, double& v) {
  c = trim(c);
  constexpr std::string_view kKey = "filament diameter";
  if (!starts_with_nocase(c, kKey)) return false;
  std::string_view rest = trim(c.substr(kKey.size()));
  if (!rest.empty() && rest.front() == '#') {
    rest.remove_prefix(1);
    while (!rest.empty() && std::isdigit(static_cast<unsigned char>(rest.front()))) rest.remove_prefix(1);
    rest = trim(rest);
  }
  if (rest.empty() || (rest.front() != ':' && rest.front() != '=')) return false;
  return first_number(rest.substr(1), v);
}

}  // namespace

void PrintArea::merge(const PrintArea& o) {
  if (!has_bed && o.has_bed) {
    has_bed = true;
    bed = o.bed;
  }
  if (!has_max_z && o.has_max_z) {
    has_max_z = true;
    max_z = o.max_z;
  }
  if (!has_print_box && o.has_print_box) {
    has_print_box = true;
    print_box = o.print_box;
  }
  if (!has_print_top && o.has_print_top) {
    has_print_top = true;
    print_top = o.print_top;
  }
  if (!has_filament_diameter && o.has_filament_diameter) {
    has_filament_diameter = true;
    filament_diameter = o.filament_diameter;
  }
  if (!has_retract_length && o.has_retract_length) {
    has_retract_length = true;
    retract_length = o.retract_length;
  }
  if (flavor.empty()) flavor = o.flavor;
}

void PrintAreaScanner::observe(std::string_view text) {
  std::size_t semi = text.find(';');
  if (semi == std::string_view::npos) return;
  observe_comment(text.substr(semi + 1));
}

void PrintAreaScanner::observe_comment(std::string_view c) {
  static constexpr std::string_view kCura[6] = {"MINX:", "MINY:", "MINZ:", "MAXX:", "MAXY:", "MAXZ:"};
  static constexpr std::string_view kGriffin[6] = {"PRINT.SIZE.MIN.X:", "PRINT.SIZE.MIN.Y:", "PRINT.SIZE.MIN.Z:",
                                                   "PRINT.SIZE.MAX.X:", "PRINT.SIZE.MAX.Y:", "PRINT.SIZE.MAX.Z:"};
  for (int i = 0; i < 6; ++i) {
    for (std::string_view key : {kCura[i], kGriffin[i]}) {
      if (c.size() > key.size() && c.substr(0, key.size()) == key) {
        double v = 0;
        if (number_of(c.substr(key.size()), v)) {
          cura_box_[i] = v;
          cura_seen_ |= 1u << i;
        }
        return;
      }
    }
  }
  constexpr std::string_view kFlavor = "FLAVOR:";
  if (c.size() > kFlavor.size() && c.substr(0, kFlavor.size()) == kFlavor) {
    if (found_.flavor.empty()) found_.flavor = std::string(trim(c.substr(kFlavor.size())));
    return;
  }
  constexpr std::string_view kSetting = "SETTING_3 ";
  if (c.size() > kSetting.size() && c.substr(0, kSetting.size()) == kSetting) {
    if (cura_settings_.size() < kMaxCuraSettings) cura_settings_.append(c.substr(kSetting.size()));
    return;
  }
  constexpr std::string_view kS3dDiameters = "filamentDiameters,";  // Simplify3D
  std::string_view value;
  Box2 box;
  double v = 0;
  if ((key_value(c, "bed_shape", value) || key_value(c, "printable_area", value)) && polygon_box(value, box)) {
    found_.has_bed = true;
    found_.bed = box;
  } else if ((key_value(c, "max_print_height", value) || key_value(c, "printable_height", value)) &&
             number_of(value, v) && v > 0) {
    found_.has_max_z = true;
    found_.max_z = v;
  } else if (key_value(c, "gcode_flavor", value)) {
    if (found_.flavor.empty()) found_.flavor = std::string(value);
  } else if (((key_value(c, "filament_diameter", value) && first_number(value, v)) ||
              (starts_with_nocase(trim(c), kS3dDiameters) && first_number(trim(c).substr(kS3dDiameters.size()), v)) ||
              filament_diameter_comment(c, v)) &&
             sane_diameter(v) && !found_.has_filament_diameter) {
    found_.has_filament_diameter = true;
    found_.filament_diameter = v;
  }
}

PrintArea PrintAreaScanner::limits() const {
  PrintArea l = found_;
  const double* b = cura_box_;
  if ((cura_seen_ & 0b011011u) == 0b011011u && b[3] >= b[0] && b[4] >= b[1]) {
    l.has_print_box = true;
    l.print_box = Box2{b[0], b[1], b[3], b[4]};
  }
  if ((cura_seen_ & 0b100000u) != 0 && b[5] > 0) {
    l.has_print_top = true;
    l.print_top = b[5];
  }
  if (!cura_settings_.empty()) {
    double w = 0, d = 0, h = 0;
    if (!l.has_bed && cura_setting(cura_settings_, "machine_width", w) &&
        cura_setting(cura_settings_, "machine_depth", d) && w > 0 && d > 0) {
      l.has_bed = true;
      bool centred = cura_settings_.find("machine_center_is_zero = True") != std::string::npos;
      l.bed = centred ? Box2{-w / 2, -d / 2, w / 2, d / 2} : Box2{0, 0, w, d};
    }
    if (!l.has_max_z && cura_setting(cura_settings_, "machine_height", h) && h > 0) {
      l.has_max_z = true;
      l.max_z = h;
    }
    double diameter = 0;
    if (!l.has_filament_diameter && cura_setting(cura_settings_, "material_diameter", diameter) &&
        sane_diameter(diameter)) {
      l.has_filament_diameter = true;
      l.filament_diameter = diameter;
    }
  }
  return l;
}

namespace {

void scan_lines(std::string_view text, bool skip_first, PrintAreaScanner& scanner) {
  MemoryLineSplitter split(text);
  RawLine raw;
  bool first = true;
  while (split.next(raw)) {
    // The tail starts mid-line; its first piece is not a whole line.
    if (first && skip_first) {
      first = false;
      continue;
    }
    first = false;
    scanner.observe(raw.text);
  }
}

}  // namespace

bool scan_file_limits(int fd, PrintArea& limits) {
  FileEnds ends;
  if (!read_file_ends(fd, kHeadBytes, kTailBytes, ends)) return false;
  PrintAreaScanner scanner;
  scan_lines(ends.head, false, scanner);
  scan_lines(ends.tail, true, scanner);
  limits = scanner.limits();
  return true;
}

PrintArea scan_text_limits(std::string_view text) {
  PrintAreaScanner scanner;
  scan_lines(text, false, scanner);
  return scanner.limits();
}

PrintArea slicer_environment(EnvironmentLookup lookup) {
  if (lookup == nullptr) lookup = [](const char* name) -> const char* { return std::getenv(name); };
  // The keys as the config block spells them; the variable is SLIC3R_ + KEY
  // in capitals, its value the config's text, read by the same rules.
  auto variable = [lookup](std::string_view key) {
    std::string name = "SLIC3R_";
    for (char k : key) name += static_cast<char>(std::toupper(static_cast<unsigned char>(k)));
    const char* value = lookup(name.c_str());
    std::string_view text = value != nullptr ? std::string_view(value) : std::string_view();
    // A value never spans lines; a stray newline ends it.
    return text.substr(0, text.find_first_of("\r\n"));
  };
  static constexpr std::string_view kKeys[] = {"bed_shape",        "printable_area",    "max_print_height",
                                               "printable_height", "filament_diameter", "gcode_flavor"};
  PrintAreaScanner scanner;
  for (std::string_view key : kKeys) {
    std::string_view value = variable(key);
    if (!value.empty()) scanner.observe("; " + std::string(key) + " = " + std::string(value));
  }
  PrintArea area = scanner.limits();
  // The retraction only from the slicer that runs the hook: a file's own
  // config does not change a tool's default (gc-pause-at keeps its 2 mm).
  double retract = 0;
  if (first_number(variable("retract_length"), retract) && retract >= 0 && retract < kMaxRetract) {
    area.has_retract_length = true;
    area.retract_length = retract;
  }
  return area;
}

PrintArea printer_facts(int fd, EnvironmentLookup lookup) {
  PrintArea area = slicer_environment(lookup), file;
  if (scan_file_limits(fd, file)) area.merge(file);
  return area;
}

bool parse_bed_size(std::string_view text, Box2& bed) {
  std::size_t x = text.find_first_of("xX");
  double w = 0, d = 0;
  if (x == std::string_view::npos || !parse_number(text.substr(0, x), w) || !parse_number(text.substr(x + 1), d) ||
      !(w > 0) || !(d > 0) || !std::isfinite(w) || !std::isfinite(d))
    return false;
  bed = Box2{0, 0, w, d};
  return true;
}

}  // namespace gcode
