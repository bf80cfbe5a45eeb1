#include "gcode/cli/pause_options.hpp"

#include <CLI/CLI.hpp>

#include <vector>

#include "gcode/transform/custom_gcode.hpp"

namespace gcode::cli {

void add_pause_options(Tool& tool, PauseOptions& o, bool with_method) {
  CLI::App& app = tool.app();
  PauseConfig& c = o.config;
  o.with_method = with_method;
  const auto& positive = gcode::cli::positive();
  const auto& non_negative = gcode::cli::non_negative();
  const char* printer = "Printer";
  app.add_option("--bed", o.bed, "Bed size WIDTHxDEPTH in mm (default: from the slicer's comments)")->type_name("WxD")->group(printer);
  app.add_option("--max-z", o.max_z, "Highest Z the printer reaches (default: from the slicer's comments; none)")
      ->type_name("MM")->check(positive)->group(printer);
  app.add_option("--park", o.park, "Park position X,Y (default: X centre of the print, Y = bed depth - 10)")
      ->type_name("X,Y")->group(printer);
  app.add_option("--min-park-z", c.min_park_z, "Raise the head to at least this Z while parked (default: none)")
      ->type_name("MM")->check(non_negative)->group(printer);

  const char* pause = "Pause";
  if (with_method) {
    app.add_option("--method", o.method, "Wait command: M0 M1 M25 M125 M226 M600 M601 @pause PAUSE G4 custom:'GCODE' none")
        ->type_name("METHOD")->capture_default_str()->group(pause);
    app.add_option("--dwell", c.dwell_seconds, "Seconds to wait with --method G4")
        ->type_name("SECONDS")->capture_default_str()->check(positive)->group(pause)
        ->each([&o](const std::string&) { o.dwell_given = true; });
  } else {
    o.method = "none";
  }
  app.add_option("--retract", c.retract,
                 "Retract mm before parking (0 = none; firmware G10 if the file uses it; default: the slicer's)")
      ->type_name("MM")->capture_default_str()->check(non_negative)->group(pause)
      ->each([&o](const std::string&) { o.retract_given = true; });
  app.add_option("--retract-speed", c.retract_speed, "Retract speed, mm/s")
      ->type_name("MM/S")->capture_default_str()->check(positive)->group(pause);
  app.add_option("--unretract-speed", c.unretract_speed, "Unretract speed, mm/s")
      ->type_name("MM/S")->capture_default_str()->check(positive)->group(pause);
  app.add_option("--lift", c.lift, "Lift mm above the highest printed Z (capped at --max-z)")
      ->type_name("MM")->capture_default_str()->check(non_negative)->group(pause);
  app.add_option("--z-speed", c.z_speed, "Z speed, mm/s")->type_name("MM/S")->capture_default_str()->check(positive)->group(pause);
  app.add_option("--travel-speed", c.travel_speed, "Travel speed to and from the park position, mm/s")
      ->type_name("MM/S")->capture_default_str()->check(positive)->group(pause);
  app.add_flag("--wait-moves", c.wait_for_moves, "Send M400 (finish moves) before the wait")->group(pause);
  app.add_option("--standby-temp", o.standby, "Hotend temperature while waiting (M104; default: unchanged)")
      ->type_name("C")->check(non_negative)->group(pause)
      ->each([&o](const std::string&) { o.standby_given = true; });
  app.add_option("--resume-temp", c.resume_temp, "Hotend temperature to resume at (default: the file's last M104/M109 target)")
      ->type_name("C")->check(positive)->group(pause);
  app.add_flag("--no-heat-wait", o.no_heat_wait, "Resume with M104 (do not wait for the temperature) instead of M109")
      ->group(pause);
  app.add_option("--message", c.message, "Text shown while paused (M0/M1 text, else M117); {layer} and {z} expand; '' = none")
      ->type_name("TEXT")->capture_default_str()->group(pause);
  app.add_option("--host-message", c.host_message, "Text sent to the host with M118 (default: none)")->type_name("TEXT")->group(pause);
  app.add_flag("--beep", c.beep, "Beep (M300) when pausing")->group(pause);
  app.add_option("--beep-ms", c.beep_ms, "Beep length, ms")->type_name("MS")->capture_default_str()->check(positive)->group(pause);
  app.add_option("--beep-hz", c.beep_hz, "Beep pitch, Hz")->type_name("HZ")->capture_default_str()->check(positive)->group(pause);
  app.add_option("--stepper-hold", c.stepper_hold, "Keep the steppers on for this many seconds while waiting (M84 S; default: firmware's)")
      ->type_name("SECONDS")->check(positive)->group(pause);
  const struct {
    const char* name;
    double* amount;
    double* speed;
    const char* help;
  } pushes[] = {
      {"unload", &c.unload, &c.unload_speed, "Unload this much filament at the park position before the wait (mm)"},
      {"reload", &c.reload, &c.reload_speed, "Load this much filament at the park position after the wait (mm)"},
      {"purge", &c.purge, &c.purge_speed, "Purge this much filament at the park position after the wait (mm)"},
      {"prime", &c.prime, &c.prime_speed, "Extra prime at the park position before returning (mm)"},
  };
  for (const auto& p : pushes) {
    std::string name(p.name), title(name);
    title[0] = static_cast<char>(title[0] - 'a' + 'A');
    app.add_option("--" + name, *p.amount, p.help)->type_name("MM")->check(non_negative)->group(pause);
    app.add_option("--" + name + "-speed", *p.speed, title + " speed, mm/s")
        ->type_name("MM/S")->capture_default_str()->check(positive)->group(pause);
  }
  app.add_option("--before", o.before, "G-code (a file, or text with \\n between lines) just before the wait")
      ->type_name("GCODE")->group(pause);
  app.add_option("--after", o.after, "G-code (a file, or text with \\n between lines) just after the wait")
      ->type_name("GCODE")->group(pause);
}

void resolve_pause_options(PauseOptions& o) {
  PauseConfig& c = o.config;
  if (!parse_pause_method(o.method, c.method, o.custom))
    throw UsageError("--method: unknown '" + o.method + "' (M0 M1 M25 M125 M226 M600 M601 @pause PAUSE G4 custom:'...' none)");
  if (o.dwell_given && c.method != PauseMethod::Dwell) throw UsageError("--dwell goes with --method G4");
  if (o.no_heat_wait && !o.standby_given) throw UsageError("--no-heat-wait goes with --standby-temp");
  if (o.max_z > 0 && c.min_park_z > o.max_z) throw UsageError("--min-park-z is above --max-z");
  if (!o.park.empty() && option_numbers(o.park, "--park").size() != 2) throw UsageError("--park: give X,Y (e.g. 110,210)");
  Box2 bed;
  if (!o.bed.empty() && !parse_bed_size(o.bed, bed))
    throw UsageError("--bed: '" + o.bed + "' is not WIDTHxDEPTH in mm (e.g. 220x220)");
  c.standby = o.standby_given;
  c.standby_temp = o.standby;
  c.wait_for_heat = !o.no_heat_wait;
}

void load_pause_texts(PauseOptions& o) {
  PauseConfig& c = o.config;
  if (c.method == PauseMethod::Custom) c.custom_wait = load_custom_gcode(o.custom);
  if (!o.before.empty()) c.before_wait = load_custom_gcode(o.before);
  if (!o.after.empty()) c.after_wait = load_custom_gcode(o.after);
}

ParkRules park_rules(const PauseOptions& o, const PrintArea& file_area, PauseConfig& config) {
  ParkRules park;
  park.area = file_area;
  if (!o.bed.empty()) {
    park.area.has_bed = true;
    parse_bed_size(o.bed, park.area.bed);
  }
  if (!o.park.empty()) {
    std::vector<double> xy = option_numbers(o.park, "--park");
    park.given = true;
    park.x = xy[0];
    park.y = xy[1];
  }
  if (o.max_z > 0) {
    park.area.has_max_z = true;
    park.area.max_z = o.max_z;
  }
  if (park.area.has_max_z) config.max_z = park.area.max_z;
  // The slicer's own retraction, when it runs the tool as its post-processing
  // script (SLIC3R_RETRACT_LENGTH).
  if (!o.retract_given && park.area.has_retract_length) config.retract = park.area.retract_length;
  if (config.max_z > 0 && config.min_park_z > config.max_z) throw InputError("--min-park-z is above the printer's height");
  return park;
}

}  // namespace gcode::cli
