// gc-pause-at: insert a clean pause (retract, park, wait, resume exactly) at
// layer boundaries. The rules are the library's: pause_stage.hpp (where),
// pause_context.hpp (park), pause_sequence.hpp (the blocks).
#include <algorithm>

#include "gcode/cli/filter.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/transform/custom_gcode.hpp"
#include "gcode/transform/pause_stage.hpp"

namespace {

using gcode::cli::UsageError;

struct Options {
  gcode::cli::FilterOptions io;
  std::string before_layer, after_layer, heights, bed, park, method = "M0", before, after;
  int every = 0;
  bool dry_run = false, no_heat_wait = false, retract_given = false;
  double max_z = 0, standby = 0;
  gcode::PauseConfig pause;
  gcode::PauseTriggers where;
  std::string custom;
};

std::vector<double> numbers(const std::string& text, const char* option) {
  std::vector<double> list;
  if (!gcode::parse_number_list(text, list)) throw UsageError(std::string(option) + ": '" + text + "' is not a list of numbers");
  return list;
}

// What the options say, checked before anything is read.
void resolve(Options& o, bool standby_given, bool dwell_given) {
  if (!o.before_layer.empty()) o.where.before = gcode::LayerRange::parse(o.before_layer);
  if (!o.after_layer.empty()) o.where.after = gcode::LayerRange::parse(o.after_layer);
  if ((o.where.before && o.where.before->needs_total()) || (o.where.after && o.where.after->needs_total()))
    throw UsageError("layers counted from the end ('-N') are not known while streaming; name them");
  if (!o.heights.empty()) {
    o.where.heights = numbers(o.heights, "--z");
    std::sort(o.where.heights.begin(), o.where.heights.end());
  }
  o.where.every = o.every;
  if (!o.where.any()) throw UsageError("nothing to do: give --before-layer, --after-layer, --z or --every");
  if (!gcode::parse_pause_method(o.method, o.pause.method, o.custom))
    throw UsageError("--method: unknown '" + o.method + "' (M0 M1 M25 M125 M226 M600 M601 @pause PAUSE G4 custom:'...' none)");
  if (dwell_given && o.pause.method != gcode::PauseMethod::Dwell) throw UsageError("--dwell goes with --method G4");
  if (o.no_heat_wait && !standby_given) throw UsageError("--no-heat-wait goes with --standby-temp");
  if (o.max_z > 0 && o.pause.min_park_z > o.max_z) throw UsageError("--min-park-z is above --max-z");
  if (!o.park.empty() && numbers(o.park, "--park").size() != 2) throw UsageError("--park: give X,Y (e.g. 110,210)");
  gcode::Box2 bed;
  if (!o.bed.empty() && !gcode::parse_bed_size(o.bed, bed))
    throw UsageError("--bed: '" + o.bed + "' is not WIDTHxDEPTH in mm (e.g. 220x220)");
  o.pause.standby = standby_given;
  o.pause.standby_temp = o.standby;
  o.pause.wait_for_heat = !o.no_heat_wait;
}

// The printer: the file's own comments, then the options.
gcode::ParkRules park_rules(const Options& o, gcode::cli::Filter& run, gcode::PauseConfig& config) {
  gcode::ParkRules park;
  park.area = run.print_area();
  if (!o.bed.empty()) {
    park.area.has_bed = true;
    gcode::parse_bed_size(o.bed, park.area.bed);
  }
  if (!o.park.empty()) {
    std::vector<double> xy = numbers(o.park, "--park");
    park.given = true;
    park.x = xy[0];
    park.y = xy[1];
  }
  if (o.max_z > 0) {
    park.area.has_max_z = true;
    park.area.max_z = o.max_z;
  }
  if (park.area.has_max_z) config.max_z = park.area.max_z;
  // The slicer's own retraction, when it runs this as its post-processing
  // script (SLIC3R_RETRACT_LENGTH).
  if (!o.retract_given && park.area.has_retract_length) config.retract = park.area.retract_length;
  if (config.max_z > 0 && config.min_park_z > config.max_z)
    throw gcode::cli::InputError("--min-park-z is above the printer's height");
  o.where.check_heights(park.area);
  return park;
}

int run(Options& o, gcode::Diagnostics& diag) {
  gcode::PauseConfig& c = o.pause;
  if (c.method == gcode::PauseMethod::Custom) c.custom_wait = gcode::load_custom_gcode(o.custom);
  if (!o.before.empty()) c.before_wait = gcode::load_custom_gcode(o.before);
  if (!o.after.empty()) c.after_wait = gcode::load_custom_gcode(o.after);
  gcode::cli::Filter run(o.io);
  gcode::ParkRules park = park_rules(o, run, c);
  gcode::PauseStage pauses(o.where, park, c, run.pipeline().precision(), diag, "gc-pause-at: ");
  run.add(pauses);
  auto verify = [&] { o.where.verify(pauses.layers(), pauses.top_layer_z()); };
  if (!o.dry_run) {
    run.write(verify);
    return 0;
  }
  pauses.set_dry_run(true);
  run.run();
  verify();
  gcode::OutputFile file(o.io.output, std::string());
  gcode::OutputBuffer out(file.fd());
  out.write(gcode::pause_table(pauses.pauses()));
  out.flush();
  file.commit();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  gcode::PauseConfig& c = o.pause;
  c.message = "Paused at layer {layer}";
  gcode::cli::Tool tool("gc-pause-at",
                        "Insert a clean pause at layer boundaries: retract, lift, park at the back of the bed, wait,\n"
                        "then heat, return to exactly where printing stopped and restore every mode.\n"
                        "The pause goes after the last move of the previous layer and before the move to the\n"
                        "next layer's Z. Several pauses may be given in one run.");
  CLI::App& app = tool.app();
  const auto& positive = gcode::cli::positive();
  const auto& non_negative = gcode::cli::non_negative();
  tool.add_filter_options(o.io, gcode::cli::kFilter & ~gcode::cli::kLayerMarker);

  const char* where = "Where (at least one; they combine)";
  app.add_option("--before-layer", o.before_layer, "Pause before these layers print (1 = first printed layer): 5, 5-9, 5,7,9-12")
      ->type_name("RANGE")->group(where);
  app.add_option("--after-layer", o.after_layer, "Pause once these layers are printed (N = before layer N+1)")
      ->type_name("RANGE")->group(where);
  app.add_option("--z", o.heights, "Pause before the first layer whose Z is above each height (mm, comma list)")
      ->type_name("HEIGHTS")->group(where);
  app.add_option("--every", o.every, "Pause every N layers (before layers N+1, 2N+1, ...)")
      ->type_name("N")->check(positive)->group(where);
  app.add_option("--layer-marker", o.io.layer_marker, "RE2 pattern of the layer comment, for files from other slicers")
      ->type_name("REGEX")->group(where);
  app.add_flag("--dry-run", o.dry_run, "List where each pause goes (layer, Z, line, park) and write no G-code")
      ->group(where)->excludes(app.get_option("-i"));

  const char* printer = "Printer";
  app.add_option("--bed", o.bed, "Bed size WIDTHxDEPTH in mm (default: from the slicer's comments)")->type_name("WxD")->group(printer);
  app.add_option("--max-z", o.max_z, "Highest Z the printer reaches (default: from the slicer's comments; none)")
      ->type_name("MM")->check(positive)->group(printer);
  app.add_option("--park", o.park, "Park position X,Y (default: X centre of the print, Y = bed depth - 10)")
      ->type_name("X,Y")->group(printer);
  app.add_option("--min-park-z", c.min_park_z, "Raise the head to at least this Z while parked (default: none)")
      ->type_name("MM")->check(non_negative)->group(printer);

  const char* pause = "Pause";
  app.add_option("--method", o.method, "Wait command: M0 M1 M25 M125 M226 M600 M601 @pause PAUSE G4 custom:'GCODE' none")
      ->type_name("METHOD")->capture_default_str()->group(pause);
  auto* dwell = app.add_option("--dwell", c.dwell_seconds, "Seconds to wait with --method G4")
                    ->type_name("SECONDS")->capture_default_str()->check(positive)->group(pause);
  auto* retract = app.add_option("--retract", c.retract,
                                 "Retract mm before parking (0 = none; firmware G10 if the file uses it; default: the slicer's)")
                      ->type_name("MM")->capture_default_str()->check(non_negative)->group(pause);
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
  auto* standby = app.add_option("--standby-temp", o.standby, "Hotend temperature while waiting (M104; default: unchanged)")
                      ->type_name("C")->check(non_negative)->group(pause);
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
  tool.check([&] {
    o.retract_given = retract->count() > 0;
    resolve(o, standby->count() > 0, dwell->count() > 0);
  });

  return tool.run(argc, argv, [&] {
    gcode::Diagnostics diag = tool.diagnostics(o.io);
    return run(o, diag);
  });
}
