#include "gcode/report/planner_limits.hpp"

#include <fmt/format.h>

#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "gcode/core/number.hpp"
#include "gcode/core/text.hpp"

namespace gcode {

namespace {

constexpr char kAxisLetters[4] = {'X', 'Y', 'Z', 'E'};

// "9000,1000" -> 9000: PrusaSlicer keeps normal and silent mode values.
double first_number(std::string_view key, std::string_view value, bool signed_value = false) {
  std::string_view first = trim(value.substr(0, value.find(',')));
  double v = 0;
  if (!parse_number(first, v) || (v < 0 && !signed_value))
    throw std::invalid_argument(fmt::format("profile: {} = {}: not a number{}", key, value, signed_value ? "" : " >= 0"));
  return v;
}

// Sets a per-axis array from "<prefix>x" .. "<prefix>e"; true if the key matched.
bool set_axis(std::array<double, 4>& arr, std::string_view prefix, std::string_view key, std::string_view value,
              double scale = 1) {
  if (key.size() != prefix.size() + 1 || key.substr(0, prefix.size()) != prefix) return false;
  static constexpr std::string_view kAxes = "xyze";
  std::size_t axis = kAxes.find(key.back());
  if (axis == std::string_view::npos) return false;
  arr[axis] = first_number(key, value) * scale;
  return true;
}

}  // namespace

bool PlannerLimits::apply(const Line& line) {
  if (line.kind != CommandKind::Standard || line.letter != 'M') return false;
  auto positive = [&](char letter, double& target, double scale = 1) {
    const Word* w = line.find(letter);
    if (w != nullptr && w->has_value && w->value() > 0) target = w->value() * scale;
  };
  switch (line.number) {
    case 201:  // max acceleration per axis, mm/s^2 (both firmwares)
      for (int a = 0; a < 4; ++a) positive(kAxisLetters[a], max_acceleration[static_cast<std::size_t>(a)]);
      return true;
    case 203: {  // max feed rate per axis: mm/s on Marlin, mm/min on RepRapFirmware
      double scale = firmware == Firmware::RepRapFirmware ? 1.0 / 60 : 1.0;
      for (int a = 0; a < 4; ++a) positive(kAxisLetters[a], max_feedrate[static_cast<std::size_t>(a)], scale);
      if (firmware == Firmware::Marlin) m203_in_mm_per_s_ = true;
      return true;
    }
    case 204: {
      // Marlin: P print, R retract, T travel; the legacy S sets print and
      // travel. RepRapFirmware: P print, T travel.
      auto capped = [](double v, double cap) { return cap > 0 && v > cap ? cap : v; };
      double s = 0;
      positive('S', s);
      if (s > 0) {
        print_acceleration = capped(s, max_print_acceleration);
        travel_acceleration = capped(s, max_travel_acceleration);
      }
      double v = 0;
      if (positive('P', v), v > 0) print_acceleration = capped(v, max_print_acceleration);
      v = 0;
      if (positive('R', v), v > 0) retract_acceleration = capped(v, max_retract_acceleration);
      v = 0;
      if (positive('T', v), v > 0) travel_acceleration = capped(v, max_travel_acceleration);
      return true;
    }
    case 205: {
      if (firmware == Firmware::RepRapFirmware) return true;  // RRF's M205 is a different command
      bool classic = false;
      for (int a = 0; a < 4; ++a) {
        const Word* w = line.find(kAxisLetters[a]);
        if (w != nullptr && w->has_value && w->value() >= 0) {
          jerk[static_cast<std::size_t>(a)] = w->value();
          classic = true;
        }
      }
      if (const Word* j = line.find('J'); j != nullptr && j->has_value && j->value() >= 0) {
        junction_deviation = j->value();
      } else if (classic) {
        junction_deviation = 0;
      }
      if (const Word* w = line.find('S'); w != nullptr && w->has_value && w->value() >= 0) min_feedrate = w->value();
      if (const Word* w = line.find('T'); w != nullptr && w->has_value && w->value() >= 0) min_travel_feedrate = w->value();
      return true;
    }
    case 207:  // firmware retraction: S length, F speed (mm/min); RepRapFirmware also R extra, T recover speed
      positive('S', fw_retract_length);
      positive('F', fw_retract_speed, 1.0 / 60);
      if (const Word* w = line.find('R'); w != nullptr && w->has_value) fw_unretract_extra = w->value();
      positive('T', fw_unretract_speed, 1.0 / 60);
      fw_retract_set_ = true;
      return true;
    case 208:  // firmware recover (Marlin): S extra length, F speed (mm/min)
      if (const Word* w = line.find('S'); w != nullptr && w->has_value) fw_unretract_extra = w->value();
      positive('F', fw_unretract_speed, 1.0 / 60);
      fw_retract_set_ = true;
      return true;
    case 566:  // RepRapFirmware's jerk: allowed instantaneous speed change, mm/min
      become_reprapfirmware();
      for (int a = 0; a < 4; ++a) positive(kAxisLetters[a], jerk[static_cast<std::size_t>(a)], 1.0 / 60);
      junction_deviation = 0;
      return true;
    default:
      return false;
  }
}

bool PlannerLimits::set(std::string_view key, std::string_view value) {
  // Our own keys, PrusaSlicer's machine_* keys and Cura's machine settings.
  if (set_axis(max_feedrate, "max_feedrate_", key, value) || set_axis(max_feedrate, "machine_max_feedrate_", key, value) ||
      set_axis(max_acceleration, "max_acceleration_", key, value) ||
      set_axis(max_acceleration, "machine_max_acceleration_", key, value) || set_axis(jerk, "jerk_", key, value) ||
      set_axis(jerk, "machine_max_jerk_", key, value))
    return true;
  if (key == "machine_max_jerk_xy") {
    jerk[0] = jerk[1] = first_number(key, value);
    return true;
  }
  if (key == "print_acceleration" || key == "machine_acceleration") {
    print_acceleration = travel_acceleration = retract_acceleration = first_number(key, value);
    return true;
  }
  if (key == "retract_acceleration") return retract_acceleration = first_number(key, value), true;
  if (key == "travel_acceleration") return travel_acceleration = first_number(key, value), true;
  // PrusaSlicer starts from these as the accelerations and caps M204 by them.
  if (key == "machine_max_acceleration_extruding" || key == "max_print_acceleration") {
    print_acceleration = max_print_acceleration = first_number(key, value);
    return true;
  }
  if (key == "machine_max_acceleration_retracting" || key == "max_retract_acceleration") {
    retract_acceleration = max_retract_acceleration = first_number(key, value);
    return true;
  }
  if (key == "machine_max_acceleration_travel" || key == "max_travel_acceleration") {
    travel_acceleration = max_travel_acceleration = first_number(key, value);
    return true;
  }
  if (key == "junction_deviation") return junction_deviation = first_number(key, value), true;
  if (key == "min_feedrate" || key == "machine_min_extruding_rate" || key == "machine_minimum_feedrate")
    return min_feedrate = first_number(key, value), true;
  if (key == "min_travel_feedrate" || key == "machine_min_travel_rate")
    return min_travel_feedrate = first_number(key, value), true;
  if (key.substr(0, 3) == "fw_") {
    double* field = key == "fw_retract_length"    ? &fw_retract_length
                    : key == "fw_retract_speed"   ? &fw_retract_speed
                    : key == "fw_unretract_extra" ? &fw_unretract_extra
                    : key == "fw_unretract_speed" ? &fw_unretract_speed
                                                  : nullptr;
    if (field == nullptr) return false;
    *field = first_number(key, value, field == &fw_unretract_extra);
    fw_retract_set_ = true;
    return true;
  }
  if (key == "firmware" || key == "gcode_flavor") {
    std::string_view v = trim(value);
    if (v == "reprapfirmware" || v == "rrf") {
      become_reprapfirmware();
    } else if (key == "firmware" && v != "marlin") {
      throw std::invalid_argument(fmt::format("profile: firmware = {}: expected marlin or reprapfirmware", v));
    } else {
      firmware = Firmware::Marlin;
    }
    return true;
  }
  return false;
}

void PlannerLimits::become_reprapfirmware() {
  if (firmware == Firmware::RepRapFirmware) return;
  firmware = Firmware::RepRapFirmware;
  if (m203_in_mm_per_s_)
    for (double& f : max_feedrate) f /= 60;
  // Its own firmware-retraction defaults (Configuration.h: DefaultRetractLength
  // 2 mm, DefaultRetractSpeed 1000 mm/min for retract and recover), unless
  // M207/M208 or the profile already said what the printer does.
  if (!fw_retract_set_) {
    fw_retract_length = 2;
    fw_retract_speed = fw_unretract_speed = 1000.0 / 60;
    fw_unretract_extra = 0;
  }
}

int PlannerLimits::load_profile_text(std::string_view text) {
  int used = 0;
  while (!text.empty()) {
    std::size_t nl = text.find('\n');
    std::string_view line = text.substr(0, nl);
    text = nl == std::string_view::npos ? std::string_view{} : text.substr(nl + 1);
    line = trim(line);
    if (!line.empty() && line.front() == ';') line = trim(line.substr(1));  // PrusaSlicer's G-code config block
    if (line.empty() || line.front() == '#') continue;
    std::size_t eq = line.find('=');
    if (eq == std::string_view::npos) continue;
    if (set(trim(line.substr(0, eq)), trim(line.substr(eq + 1)))) ++used;
  }
  return used;
}

std::string_view PlannerLimits::preset(std::string_view name) {
  if (name == "marlin") return "# Marlin 2.1 defaults: the built-in starting point\n";
  if (name == "cura")
    return "# CuraEngine's fdmprinter machine defaults (unlimited feed rates)\n"
           "machine_max_feedrate_x = 299792458000\nmachine_max_feedrate_y = 299792458000\n"
           "machine_max_feedrate_z = 299792458000\nmachine_max_feedrate_e = 299792458000\n"
           "machine_max_acceleration_x = 9000\nmachine_max_acceleration_y = 9000\n"
           "machine_max_acceleration_z = 100\nmachine_max_acceleration_e = 10000\n"
           "machine_acceleration = 4000\n"
           "machine_max_jerk_xy = 20\nmachine_max_jerk_z = 0.4\nmachine_max_jerk_e = 5\n"
           "# CuraEngine plans a firmware retraction (G10) as its retraction distance (5 mm here)\n"
           "# at 25 mm/s, and the recover (G11) as no move at all.\n"
           "fw_retract_length = 5\nfw_retract_speed = 25\nfw_unretract_extra = -5\n";
  return {};
}

int PlannerLimits::load_file_config(int fd) {
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_size <= 0) return 0;
  constexpr off_t kTail = 64 << 10;
  off_t from = st.st_size > kTail ? st.st_size - kTail : 0;
  std::vector<char> buffer(static_cast<std::size_t>(st.st_size - from));
  std::size_t got = 0;
  while (got < buffer.size()) {
    ssize_t n = ::pread(fd, buffer.data() + got, buffer.size() - got, from + static_cast<off_t>(got));
    if (n <= 0) break;
    got += static_cast<std::size_t>(n);
  }
  std::string_view tail(buffer.data(), got);
  std::size_t begin = tail.find("; prusaslicer_config = begin");
  if (begin == std::string_view::npos) return 0;
  tail = tail.substr(begin);
  if (tail.find("; machine_limits_usage = ignore") != std::string_view::npos) return 0;
  return load_profile_text(tail);
}

int PlannerLimits::load_profile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::string_view built_in = preset(path);
    if (!built_in.empty()) return load_profile_text(built_in);
    throw std::runtime_error(fmt::format("{}: cannot read the profile", path));
  }
  std::ostringstream all;
  all << in.rdbuf();
  return load_profile_text(all.str());
}

std::vector<std::string> PlannerLimits::describe() const {
  std::vector<std::string> lines;
  lines.push_back(fmt::format(
      "limits: firmware {}; max feed rate X{:g} Y{:g} Z{:g} E{:g} mm/s; max acceleration X{:g} Y{:g} Z{:g} E{:g} mm/s^2",
      firmware == Firmware::Marlin ? "Marlin" : "RepRapFirmware", max_feedrate[0], max_feedrate[1], max_feedrate[2],
      max_feedrate[3], max_acceleration[0], max_acceleration[1], max_acceleration[2], max_acceleration[3]));
  std::string s = fmt::format("limits: acceleration print {:g} travel {:g} retract {:g} mm/s^2", print_acceleration,
                              travel_acceleration, retract_acceleration);
  if (max_print_acceleration > 0 || max_travel_acceleration > 0 || max_retract_acceleration > 0)
    s += fmt::format(" (caps {:g}/{:g}/{:g})", max_print_acceleration, max_travel_acceleration,
                     max_retract_acceleration);
  lines.push_back(std::move(s));
  if (junction_deviation > 0)
    s = fmt::format("limits: junction deviation {:g} mm", junction_deviation);
  else
    s = fmt::format("limits: classic jerk X{:g} Y{:g} Z{:g} E{:g} mm/s", jerk[0], jerk[1], jerk[2], jerk[3]);
  s += fmt::format("; min feed rate {:g}, travel {:g} mm/s; firmware retraction {:g} mm at {:g} mm/s", min_feedrate,
                   min_travel_feedrate, fw_retract_length, fw_retract_speed);
  lines.push_back(std::move(s));
  return lines;
}

}  // namespace gcode
