#include "gcode/cli/speed_options.hpp"

#include <CLI/CLI.hpp>

#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "gcode/core/number.hpp"

namespace gcode::cli {

namespace {

constexpr double kDefaultFilament = 1.75;

// "F1:F2", both above 0.
void parse_ramp(const std::string& text, SpeedOptions& s) {
  std::size_t colon = text.find(':');
  if (colon == std::string::npos || !parse_number(text.substr(0, colon), s.ramp_first) ||
      !parse_number(text.substr(colon + 1), s.ramp_last))
    throw UsageError("--ramp: '" + text + "' is not F1:F2 (e.g. 1:3)");
  s.ramp = true;
}

}  // namespace

void add_speed_options(Tool& tool, SpeedToolOptions& o) {
  SpeedOptions& s = o.speed;
  CLI::App& app = tool.app();
  tool.add_filter_options(o.io);

  const char* change = "Change (one of)";
  auto* factor = app.add_option("--factor", s.factor, "Multiply the speed by F (3 = three times as fast, 0.5 = half)")
                     ->type_name("F")->check(positive())->group(change);
  auto* speed = app.add_option("--speed", s.speed, "Print every changed move at this speed, mm/s")
                    ->type_name("MM_S")->check(positive())->group(change);
  auto* ramp = app.add_option("--ramp", o.ramp, "Factor F1 on the first layer of the region to F2 on its last, linearly")
                   ->type_name("F1:F2")->group(change);
  factor->excludes(speed)->excludes(ramp);
  speed->excludes(ramp);
  tool.add_selection(o.where, "Change only in");

  const char* what = "What changes (extruding moves by default)";
  auto* travel = app.add_flag("--travel", s.travel, "Travel moves too, by the same change (never Z moves, retractions or wipes)")
                     ->group(what);
  app.add_option("--travel-factor", s.travel_factor, "Travel moves too, by this factor")
      ->type_name("F")->check(positive())->group(what)->excludes(travel);

  const char* limits = "Limits, for changed moves";
  app.add_option("--max-speed", s.max_speed, "At most this speed, mm/s")->type_name("MM_S")->check(positive())->group(limits);
  app.add_option("--min-speed", s.min_speed, "At least this speed, mm/s")->type_name("MM_S")->check(positive())->group(limits);
  app.add_option("--max-flow", s.max_flow, "At most this volume of filament per second (the hot end's melt rate), mm3/s")
      ->type_name("MM3_S")->check(positive())->group(limits);
  auto* diameter = app.add_option("--filament-diameter", s.filament_diameter,
                                  "Filament diameter for --max-flow, mm (default: the file's, else 1.75)")
                       ->type_name("MM")->check(positive())->group(limits);

  const char* firmware = "Firmware factor instead of F";
  auto* m220 = app.add_flag("--m220", s.m220, "Insert M220 S<percent> at the region's start and the restore at its end")
                   ->group(firmware);
  auto* restore = app.add_option("--m220-restore", o.m220_restore,
                                 "auto: M220 B/R if the file says Marlin 2, else M220 S100; backup: M220 B/R; reset: M220 S100")
                      ->type_name("auto|backup|reset")->check(CLI::IsMember({"auto", "backup", "reset"}))
                      ->capture_default_str()->group(firmware);
  app.add_flag("--force", s.force, "Change lines an earlier gc-speedup run changed (the factors multiply)");

  tool.check([&o, &s, factor, speed, ramp, restore, m220, diameter] {
    if (factor->count() + speed->count() + ramp->count() == 0)
      throw UsageError("give the change: --factor F, --speed MM_S or --ramp F1:F2");
    if (ramp->count() > 0) parse_ramp(o.ramp, s);
    if (restore->count() > 0 && m220->count() == 0) throw UsageError("--m220-restore goes with --m220");
    if (o.m220_restore == "reset") s.m220_restore = M220Restore::Reset;
    o.diameter_given = diameter->count() > 0;
    s.validate();  // std::invalid_argument in a check: a usage error
  });
}

void resolve_speed_from_input(SpeedToolOptions& o, Filter& run, const LayerSelection& where, Diagnostics& diag) {
  SpeedOptions& s = o.speed;
  if (s.ramp) {
    // The ramp runs across the region's layers: know them before writing.
    // The selection read the file already when it names --types.
    const InputScan& scan = run.scan();
    for (const LayerInfo& layer : scan.layers)
      if (!where.by_layer() || where.layer_selected(layer)) s.ramp_layers.push_back(layer.index);
  }
  if ((s.max_flow > 0 && !o.diameter_given) || (s.m220 && o.m220_restore == "auto")) {
    PrintArea printer = run.print_area();
    if (s.max_flow > 0 && !o.diameter_given) {
      s.filament_diameter = printer.has_filament_diameter ? printer.filament_diameter : kDefaultFilament;
      if (!printer.has_filament_diameter)
        diag.warn(fmt::format("{} names no filament diameter; --max-flow assumes {} mm (give --filament-diameter)",
                              run.input().name(), kDefaultFilament));
    }
    if (s.m220) s.m220_restore = m220_restore_for_flavor(printer.flavor);
  }
  if (o.m220_restore == "backup") s.m220_restore = M220Restore::Backup;
  if (s.m220 && !s.ramp && std::fabs(s.factor * 100 - std::round(s.factor * 100)) > 1e-9)
    diag.warn(fmt::format("--m220: the firmware takes whole percents; x{} is written M220 S{}", s.factor,
                          std::lround(s.factor * 100)));
}

void report_speed_change(const SpeedOptions& s, const SpeedStats& stats, Diagnostics& diag) {
  if (stats.capped() > 0) {
    std::vector<std::string> parts;
    if (stats.capped_flow > 0)
      parts.push_back(fmt::format("{} by --max-flow {} mm3/s (filament {} mm)", stats.capped_flow,
                                  number_string(s.max_flow, 3), number_string(s.filament_diameter, 3)));
    if (stats.capped_max_speed > 0)
      parts.push_back(fmt::format("{} by --max-speed {} mm/s", stats.capped_max_speed, number_string(s.max_speed, 3)));
    if (stats.capped_min_speed > 0)
      parts.push_back(fmt::format("{} by --min-speed {} mm/s", stats.capped_min_speed, number_string(s.min_speed, 3)));
    diag.warn(fmt::format("{} moves capped: {}", stats.capped(), fmt::join(parts, ", ")));
  }
  if (stats.left_alone > 0) diag.warn(fmt::format("{} moves of the region left at their speed", stats.left_alone));
  if (s.m220) {
    diag.info(fmt::format("{} M220 lines inserted; {} moves in {} layers run at the changed factor", stats.m220_lines,
                          stats.moves_changed, stats.layers.size()));
  } else {
    diag.info(fmt::format("{} moves in {} layers at a new speed; {} lines edited ({} put the original F back)",
                          stats.moves_changed, stats.layers.size(), stats.lines_edited, stats.restores));
  }
}

}  // namespace gcode::cli
