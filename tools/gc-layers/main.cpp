// gc-layers: see a G-code file by layer, and cut it by layer (the options of
// cli/layers_options.hpp, the reports of lib/report, the cut of transform/layer_extract.hpp).
#include <fmt/format.h>

#include <optional>

#include "gcode/cli/filter.hpp"
#include "gcode/cli/layers_options.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/report/feature_time.hpp"
#include "gcode/report/layer_report.hpp"
#include "gcode/report/layer_svg.hpp"
#include "gcode/report/layer_table.hpp"
#include "gcode/report/layer_time.hpp"
#include "gcode/transform/layer_extract.hpp"

namespace {

using gcode::cli::InputError;

using Options = gcode::cli::LayersToolOptions;

std::string no_such_layer(int layer, gcode::cli::Filter& run, int layers) {
  return fmt::format("layer {} does not exist: {} has {} layers", layer, run.input().name(), layers);
}

void check_has_layers(gcode::cli::Filter& run) {
  if (run.pipeline().bytes_read() == 0) throw InputError(run.input().name() + ": empty input");
  if (run.pipeline().tracker().layer_count() == 0)
    throw InputError(run.input().name() + ": no extrusion found (is this a print file?)");
}

// --svg / --svg-sheet: the pictures, to the path(s) of --svg-out (or stdout).
void write_pictures(const Options& o, gcode::LayerDrawer& drawer, const gcode::LayerTimes& times,
                    const gcode::PrintArea& printer, gcode::cli::Filter& run) {
  gcode::SvgOptions svg;
  svg.travel = !o.no_travel;
  svg.size_px = o.svg_size;
  const gcode::LayerTracker& tracker = run.pipeline().tracker();
  for (int i = 0; i < tracker.feature_count(); ++i) svg.feature_names.push_back(tracker.feature_name(i));
  if (printer.has_bed) svg.bed = printer.bed.outline();
  gcode::write_layer_pictures(drawer.drawings(), svg, times.layers, !o.svg_sheet.empty(), o.svg_out,
                              [](const std::string& path, const std::string& text) {
                                gcode::cli::write_output_file(path, [&](gcode::OutputBuffer& out) { out.write(text); });
                              });
}

int run(Options& o, gcode::Diagnostics& diag) {
  gcode::cli::Filter run(o.io);
  std::optional<gcode::LayerRange> range, picture_range;
  std::optional<gcode::ZRange> zr;
  if (!o.extract.empty()) range = gcode::LayerRange::parse(o.extract);
  if (!o.z_range.empty()) zr = gcode::ZRange::parse(o.z_range);
  if (o.pictures()) picture_range = gcode::LayerRange::parse(o.svg.empty() ? o.svg_sheet : o.svg);
  int total = 0;
  if ((range && range->needs_total()) || (picture_range && picture_range->needs_total())) total = run.count_layers();
  // Read once, after counting (a pipe is a temp file by then): the filament and the bed.
  const gcode::PrintArea printer = gcode::printer_facts(run.input().fd());
  if (o.filament_diameter == 0) o.filament_diameter = printer.has_filament_diameter ? printer.filament_diameter : 1.75;

  // The table of every layer is for the reports; a cut needs only the count
  // (the tracker's), and leaving the table out is 4 % of a cut's work.
  std::optional<gcode::LayerTable> table;
  if (!o.cutting()) run.add(table.emplace());
  std::optional<gcode::LayerTimer> timer;
  std::optional<gcode::FeatureTimer> feature_timer;
  if (o.time || picture_range) {
    gcode::EstimatorOptions estimate;
    estimate.heat_time = !o.no_heat_time;
    estimate.limits.load_file_config(run.input().fd());
    if (!o.profile.empty()) estimate.limits.load_profile(o.profile);
    timer.emplace(estimate);
    run.add(*timer);
    if (o.time_by_feature) run.add(feature_timer.emplace(estimate));
  }
  std::optional<gcode::LayerDrawer> drawer;
  if (picture_range) {
    drawer.emplace([&](int layer) { return picture_range->contains(layer, total); }, o.filament_diameter);
    run.add(*drawer);
  }
  std::optional<gcode::LayerExtractor> extractor;
  auto layers = [&] { return run.pipeline().tracker().layer_count(); };
  if (o.cutting()) {
    gcode::ExtractOptions extract;
    extract.note_prefix = "gc-layers: ";
    extractor.emplace(
        [&](const gcode::LayerInfo& l) { return (!range || range->contains(l.index, total)) && (!zr || zr->contains(l.z)); },
        run.pipeline().precision(), extract);
    run.add(*extractor);
    run.write([&] {
      check_has_layers(run);
      if (range && range->highest_named() > layers()) throw InputError(no_such_layer(range->highest_named(), run, layers()));
      if (extractor->layers_written() == 0) throw InputError("no layer matches the selection");
    });
    diag.info(fmt::format("wrote {} of {} layers", extractor->layers_written(), layers()));
    return 0;
  }
  run.run();
  check_has_layers(run);
  if (timer)
    for (const std::string& line : timer->estimator().limits().describe()) diag.info(line);
  if (drawer) {
    if (picture_range->highest_named() > layers()) throw InputError(no_such_layer(picture_range->highest_named(), run, layers()));
    write_pictures(o, *drawer, timer->times(), printer, run);
    return 0;
  }
  if (o.where > 0) {
    if (o.where > layers()) throw InputError(no_such_layer(o.where, run, layers()));
    const gcode::LayerRow& r = table->layers()[static_cast<std::size_t>(o.where - 1)];
    fmt::print("{} {} {} {}\n", r.first_line, r.last_line, r.byte_begin, r.byte_end);
    return 0;
  }
  const gcode::LayerTracker& tracker = run.pipeline().tracker();
  gcode::ReportOptions report{run.input().name(), o.density, o.filament_diameter, tracker.mode()};
  if (timer) report.times = &timer->times();
  gcode::FeatureTimes features;
  if (feature_timer) report.features = &(features = feature_timer->times([&](int id) { return tracker.feature_name(id); }));
  std::string text = o.json ? gcode::layer_table_json(*table, tracker, report) : gcode::layer_table_text(*table, tracker, report);
  gcode::cli::write_output_file("", [&](gcode::OutputBuffer& out) { out.write(text); });
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return gcode::cli::run_filter(
      argc, argv, "gc-layers",
      "gc-layers: show a G-code file layer by layer (lines, bytes, Z, filament, features), or cut it by layer.\n"
      "Layers come from slicer markers (Cura, PrusaSlicer, Slic3r, Orca, Simplify3D) or, in unmarked files,\n"
      "from the Z of extrusions. The first printed layer is 1.",
      gcode::cli::add_layers_options, run);
}
