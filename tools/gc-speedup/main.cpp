// gc-speedup: change print speed by layer, height or feature, exactly: every
// move that inherits F is changed too, and the original F is back on the
// first move after the region. The rules are the library's (transform/speed.hpp).
#include <fmt/format.h>

#include <cmath>
#include <optional>

#include "gcode/cli/filter.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/core/feature.hpp"
#include "gcode/core/number.hpp"
#include "gcode/report/layer_time.hpp"
#include "gcode/transform/speed.hpp"

namespace {

using gcode::cli::UsageError;

constexpr double kDefaultFilament = 1.75;

struct Options {
  gcode::cli::FilterOptions io;
  gcode::SelectionText where;
  gcode::SpeedOptions speed;
  std::string ramp;
  std::string m220_restore = "auto";
};

// "F1:F2", both above 0.
void parse_ramp(const std::string& text, gcode::SpeedOptions& s) {
  std::size_t colon = text.find(':');
  if (colon == std::string::npos || !gcode::parse_number(text.substr(0, colon), s.ramp_first) ||
      !gcode::parse_number(text.substr(colon + 1), s.ramp_last))
    throw UsageError("--ramp: '" + text + "' is not F1:F2 (e.g. 1:3)");
  s.ramp = true;
}

std::string seconds(double s) { return fmt::format("{:.1f} s", s); }

// -v: the estimate before and after, per layer of the region and in total.
void report_time(gcode::Diagnostics& diag, const gcode::LayerTimer& before, const gcode::LayerTimer& after,
                 const std::vector<int>& layers) {
  const gcode::LayerTimes &a = before.times(), &b = after.times();
  for (int layer : layers) {
    auto i = static_cast<std::size_t>(layer - 1);
    if (i < a.layers.size() && i < b.layers.size())
      diag.info(fmt::format("layer {}: {} -> {}", layer, seconds(a.layers[i]), seconds(b.layers[i])));
  }
  double t0 = a.total(), t1 = b.total();
  diag.info(fmt::format("estimated print time {} -> {} ({:+.1f} %)", gcode::format_duration(t0),
                        gcode::format_duration(t1), t0 > 0 ? 100 * (t1 - t0) / t0 : 0.0));
}

void report_caps(gcode::Diagnostics& diag, const gcode::SpeedOptions& o, const gcode::SpeedStats& s) {
  if (s.capped() == 0) return;
  std::vector<std::string> parts;
  char buffer[gcode::kMaxNumberChars];
  auto mm = [&](double v) { return std::string(gcode::number_text(v, 3, buffer)); };
  if (s.capped_flow > 0)
    parts.push_back(fmt::format("{} by --max-flow {} mm3/s (filament {} mm)", s.capped_flow, mm(o.max_flow),
                                mm(o.filament_diameter)));
  if (s.capped_max_speed > 0) parts.push_back(fmt::format("{} by --max-speed {} mm/s", s.capped_max_speed, mm(o.max_speed)));
  if (s.capped_min_speed > 0) parts.push_back(fmt::format("{} by --min-speed {} mm/s", s.capped_min_speed, mm(o.min_speed)));
  diag.warn(fmt::format("{} moves capped: {}", s.capped(), fmt::join(parts, ", ")));
}

int run(Options& o, gcode::cli::Tool& tool, bool diameter_given) {
  gcode::Diagnostics diag = tool.diagnostics(o.io);
  gcode::SpeedOptions& s = o.speed;
  gcode::cli::Filter run(o.io);
  gcode::LayerSelection where = run.selection(o.where);
  if (s.ramp) {
    // The ramp runs across the region's layers: know them before writing.
    gcode::cli::InputScan scan = run.scan();
    gcode::cli::check_types(where.types(), scan.features);
    for (const gcode::LayerInfo& layer : scan.layers)
      if (!where.by_layer() || where.layer_selected(layer)) s.ramp_layers.push_back(layer.index);
  }
  if ((s.max_flow > 0 && !diameter_given) || (s.m220 && o.m220_restore == "auto")) {
    gcode::PrintArea printer = run.print_area();
    if (s.max_flow > 0 && !diameter_given) {
      s.filament_diameter = printer.has_filament_diameter ? printer.filament_diameter : kDefaultFilament;
      if (!printer.has_filament_diameter)
        diag.warn(fmt::format("{} names no filament diameter; --max-flow assumes {} mm (give --filament-diameter)",
                              run.input().name(), kDefaultFilament));
    }
    // M220 B/R: Marlin 2 and Prusa firmware; elsewhere they may be ignored,
    // which would leave the printer at the changed speed.
    if (s.m220) s.m220_restore = gcode::same_name(printer.flavor, "marlin2") ? gcode::M220Restore::Backup : gcode::M220Restore::Reset;
  }
  if (o.m220_restore == "backup") s.m220_restore = gcode::M220Restore::Backup;
  if (s.m220 && !s.ramp && std::fabs(s.factor * 100 - std::round(s.factor * 100)) > 1e-9)
    diag.warn(fmt::format("--m220: the firmware takes whole percents; x{} is written M220 S{}", s.factor,
                          std::lround(s.factor * 100)));

  gcode::SpeedStage stage(s, run.pipeline().precision(), &diag, &where);
  std::optional<gcode::LayerTimer> before, after;
  if (o.io.verbosity() >= 1) {
    before.emplace();
    run.add(*before);
  }
  run.add(stage);
  if (o.io.verbosity() >= 1) {
    after.emplace();
    run.add(*after);
  }
  run.write([&] { run.check_selection(where, diag, "changed"); });
  const gcode::SpeedStats& stats = stage.stats();
  report_caps(diag, s, stats);
  if (stats.left_alone > 0) diag.warn(fmt::format("{} moves of the region left at their speed", stats.left_alone));
  if (s.m220) {
    diag.info(fmt::format("{} M220 lines inserted; {} moves in {} layers run at the changed factor", stats.m220_lines,
                          stats.moves_changed, stats.layers.size()));
  } else {
    diag.info(fmt::format("{} moves in {} layers at a new speed; {} lines edited ({} put the original F back)",
                          stats.moves_changed, stats.layers.size(), stats.lines_edited, stats.restores));
  }
  if (before && after) report_time(diag, *before, *after, stats.layers);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  gcode::SpeedOptions& s = o.speed;
  gcode::cli::Tool tool(
      "gc-speedup",
      "gc-speedup: change print speed by layer, height or feature, exactly. F is modal: every move of the\n"
      "region runs at its original speed times the factor, also moves that inherit F, and the first move\n"
      "after the region gets its original F back. Positions, E and every other line stay byte for byte;\n"
      "an edited line gets a '; gc-speedup x3' comment, and a region already changed is refused.\n"
      "  gc-speedup --factor 0.5 --layers 1-3 part.gcode | gc-send --port /dev/ttyACM0\n"
      "  gc-speedup --factor 1.5 --types FILL --max-flow 12 -i part.gcode");
  CLI::App& app = tool.app();
  const auto& positive = gcode::cli::positive();
  tool.add_filter_options(o.io);

  const char* change = "Change (one of)";
  auto* factor = app.add_option("--factor", s.factor, "Multiply the speed by F (3 = three times as fast, 0.5 = half)")
                     ->type_name("F")->check(positive)->group(change);
  auto* speed = app.add_option("--speed", s.speed, "Print every changed move at this speed, mm/s")
                    ->type_name("MM_S")->check(positive)->group(change);
  auto* ramp = app.add_option("--ramp", o.ramp, "Factor F1 on the first layer of the region to F2 on its last, linearly")
                   ->type_name("F1:F2")->group(change);
  factor->excludes(speed)->excludes(ramp);
  speed->excludes(ramp);
  tool.add_selection(o.where, "Change only in");

  const char* what = "What changes (extruding moves by default)";
  auto* travel = app.add_flag("--travel", s.travel, "Travel moves too, by the same change (never Z moves, retractions or wipes)")
                     ->group(what);
  app.add_option("--travel-factor", s.travel_factor, "Travel moves too, by this factor")
      ->type_name("F")->check(positive)->group(what)->excludes(travel);

  const char* limits = "Limits, for changed moves";
  app.add_option("--max-speed", s.max_speed, "At most this speed, mm/s")->type_name("MM_S")->check(positive)->group(limits);
  app.add_option("--min-speed", s.min_speed, "At least this speed, mm/s")->type_name("MM_S")->check(positive)->group(limits);
  app.add_option("--max-flow", s.max_flow, "At most this volume of filament per second (the hot end's melt rate), mm3/s")
      ->type_name("MM3_S")->check(positive)->group(limits);
  auto* diameter = app.add_option("--filament-diameter", s.filament_diameter,
                                  "Filament diameter for --max-flow, mm (default: the file's, else 1.75)")
                       ->type_name("MM")->check(positive)->group(limits);

  const char* firmware = "Firmware factor instead of F";
  auto* m220 = app.add_flag("--m220", s.m220, "Insert M220 S<percent> at the region's start and the restore at its end")
                   ->group(firmware);
  auto* restore = app.add_option("--m220-restore", o.m220_restore,
                                 "auto: M220 B/R if the file says Marlin 2, else M220 S100; backup: M220 B/R; reset: M220 S100")
                      ->type_name("auto|backup|reset")->check(CLI::IsMember({"auto", "backup", "reset"}))
                      ->capture_default_str()->group(firmware);
  app.add_flag("--force", s.force, "Change lines an earlier gc-speedup run changed (the factors multiply)");

  tool.check([&] {
    if (factor->count() + speed->count() + ramp->count() == 0)
      throw UsageError("give the change: --factor F, --speed MM_S or --ramp F1:F2");
    if (ramp->count() > 0) parse_ramp(o.ramp, s);
    if (restore->count() > 0 && m220->count() == 0) throw UsageError("--m220-restore goes with --m220");
    if (o.m220_restore == "reset") s.m220_restore = gcode::M220Restore::Reset;
    try {
      s.validate();
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  });

  return tool.run(argc, argv, [&] { return run(o, tool, diameter->count() > 0); });
}
