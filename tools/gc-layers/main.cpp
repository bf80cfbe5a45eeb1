// gc-layers: see a G-code file by layer, and cut it by layer.
#include <fmt/format.h>

#include <optional>

#include "gcode/cli/filter.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/report/layer_report.hpp"
#include "gcode/report/layer_svg.hpp"
#include "gcode/report/layer_table.hpp"
#include "gcode/report/layer_time.hpp"
#include "gcode/transform/layer_extract.hpp"

namespace {

using gcode::cli::InputError;
using gcode::cli::UsageError;

struct Options {
  gcode::cli::FilterOptions io;
  bool json = false;
  std::string extract;
  std::string z_range;
  int where = 0;
  double density = 1.24;
  double filament_diameter = 0;  // 0: the slicer's (environment or file), else 1.75
  // --time, --svg, --svg-sheet
  bool time = false;
  std::string profile;
  bool no_heat_time = false;
  std::string svg;
  std::string svg_sheet;
  std::string svg_out;
  bool no_travel = false;
  double svg_size = 800;

  bool cutting() const { return !extract.empty() || !z_range.empty(); }
  bool pictures() const { return !svg.empty() || !svg_sheet.empty(); }
};

std::string no_such_layer(int layer, gcode::cli::Filter& run, int layers) {
  return fmt::format("layer {} does not exist: {} has {} layers", layer, run.input().name(), layers);
}

// --svg / --svg-sheet: the pictures, to the path(s) of --svg-out (or stdout).
void write_pictures(const Options& o, gcode::LayerDrawer& drawer, const gcode::LayerTimes& times,
                    gcode::cli::Filter& run) {
  std::vector<gcode::LayerDrawing>& drawings = drawer.drawings();
  if (drawings.empty()) throw InputError("no layer matches the selection");
  gcode::SvgOptions svg;
  svg.travel = !o.no_travel;
  svg.size_px = o.svg_size;
  const gcode::LayerTracker& tracker = run.pipeline().tracker();
  for (int i = 0; i < tracker.feature_count(); ++i) svg.feature_names.push_back(tracker.feature_name(i));
  gcode::PrintArea area = gcode::printer_facts(run.input().fd());
  if (area.has_bed) svg.bed = area.bed.outline();
  for (gcode::LayerDrawing& d : drawings) {
    auto i = static_cast<std::size_t>(d.layer - 1);
    d.seconds = i < times.layers.size() ? times.layers[i] : -1;
  }
  auto write = [](const std::string& path, const std::string& text) {
    gcode::OutputFile file(path, std::string());
    gcode::OutputBuffer buffer(file.fd());
    buffer.write(text);
    buffer.flush();
    file.commit();
  };
  if (!o.svg_sheet.empty()) {
    write(o.svg_out, gcode::layer_sheet_svg(drawings, svg));
    return;
  }
  if (drawings.size() > 1 && !gcode::has_layer_placeholder(o.svg_out))
    throw InputError("several layers selected: give --svg-out a pattern such as layer-{}.svg");
  for (const gcode::LayerDrawing& d : drawings)
    write(gcode::expand_layer_pattern(o.svg_out, d.layer), gcode::layer_svg(d, svg));
}

void check_has_layers(const gcode::LayerTable& table, gcode::cli::Filter& run) {
  if (table.total_bytes() == 0) throw InputError(run.input().name() + ": empty input");
  if (table.layers().empty()) throw InputError(run.input().name() + ": no extrusion found (is this a print file?)");
}

int run(Options& o, gcode::Diagnostics& diag) {
  gcode::cli::Filter run(o.io);
  if (o.filament_diameter == 0) {
    gcode::PrintArea printer = gcode::printer_facts(run.input().fd());
    o.filament_diameter = printer.has_filament_diameter ? printer.filament_diameter : 1.75;
  }
  std::optional<gcode::LayerRange> range, picture_range;
  std::optional<gcode::ZRange> zr;
  if (!o.extract.empty()) range = gcode::LayerRange::parse(o.extract);
  if (!o.z_range.empty()) zr = gcode::ZRange::parse(o.z_range);
  if (o.pictures()) picture_range = gcode::LayerRange::parse(o.svg.empty() ? o.svg_sheet : o.svg);
  int total = 0;
  if ((range && range->needs_total()) || (picture_range && picture_range->needs_total())) total = run.count_layers();

  gcode::LayerTable table;
  run.add(table);
  std::optional<gcode::LayerTimer> timer;
  if (o.time || picture_range) {
    gcode::EstimatorOptions estimate;
    estimate.heat_time = !o.no_heat_time;
    estimate.limits.load_file_config(run.input().fd());
    if (!o.profile.empty()) estimate.limits.load_profile(o.profile);
    timer.emplace(estimate);
    run.add(*timer);
  }
  std::optional<gcode::LayerDrawer> drawer;
  if (picture_range) {
    drawer.emplace([&](int layer) { return picture_range->contains(layer, total); }, o.filament_diameter);
    run.add(*drawer);
  }
  std::optional<gcode::LayerExtractor> extractor;
  auto layers = [&] { return static_cast<int>(table.layers().size()); };
  if (o.cutting()) {
    gcode::ExtractOptions extract;
    extract.note_prefix = "gc-layers: ";
    extractor.emplace(
        [&](const gcode::LayerInfo& l) { return (!range || range->contains(l.index, total)) && (!zr || zr->contains(l.z)); },
        run.pipeline().precision(), extract);
    run.add(*extractor);
    run.write([&] {
      check_has_layers(table, run);
      if (range && range->highest_named() > layers()) throw InputError(no_such_layer(range->highest_named(), run, layers()));
      if (extractor->layers_written() == 0) throw InputError("no layer matches the selection");
    });
    diag.info(fmt::format("wrote {} of {} layers", extractor->layers_written(), layers()));
    return 0;
  }
  run.run();
  check_has_layers(table, run);
  if (timer)
    for (const std::string& line : timer->estimator().limits().describe()) diag.info(line);
  if (drawer) {
    if (picture_range->highest_named() > layers()) throw InputError(no_such_layer(picture_range->highest_named(), run, layers()));
    write_pictures(o, *drawer, timer->times(), run);
    return 0;
  }
  if (o.where > 0) {
    if (o.where > layers()) throw InputError(no_such_layer(o.where, run, layers()));
    const gcode::LayerRow& r = table.layers()[static_cast<std::size_t>(o.where - 1)];
    fmt::print("{} {} {} {}\n", r.first_line, r.last_line, r.byte_begin, r.byte_end);
    return 0;
  }
  const gcode::LayerTracker& tracker = run.pipeline().tracker();
  gcode::ReportOptions report{run.input().name(), o.density, o.filament_diameter, tracker.mode()};
  if (timer) report.times = &timer->times();
  std::string text = o.json ? gcode::layer_table_json(table, tracker, report) : gcode::layer_table_text(table, tracker, report);
  gcode::OutputBuffer stdout_buffer(1);
  stdout_buffer.write(text);
  stdout_buffer.flush();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  gcode::cli::Tool tool(
      "gc-layers",
      "gc-layers: show a G-code file layer by layer (lines, bytes, Z, filament, features), or cut it by layer.\n"
      "Layers come from slicer markers (Cura, PrusaSlicer, Slic3r, Orca, Simplify3D) or, in unmarked files,\n"
      "from the Z of extrusions. The first printed layer is 1.");
  CLI::App& app = tool.app();
  tool.add_filter_options(o.io);
  app.add_flag("--json", o.json, "Print the table as JSON (schema gc-layers/1, see the man page)");
  app.add_option("--extract", o.extract,
                 "Write start code, the layers in RANGE and end code as printable G-code "
                 "(RANGE: 5, 5-9, 5-, -3 for the last three, 5,7,9-12)")
      ->type_name("RANGE");
  app.add_option("--z-range", o.z_range, "Write the layers whose Z lies in Z1:Z2 (either side may be empty)")
      ->type_name("Z1:Z2");
  app.add_option("--where", o.where, "Print first line, last line, first byte and end byte of layer N")
      ->type_name("N")
      ->check(gcode::cli::positive());
  app.add_option("--density", o.density, "Filament density in g/cm3 for the mass (default PLA 1.24)")
      ->check(gcode::cli::positive());
  app.add_option("--filament-diameter", o.filament_diameter, "Filament diameter in mm (default: the slicer's, else 1.75)")
      ->check(gcode::cli::positive());
  app.add_flag("--time", o.time,
               "Add the estimated print time per layer and cumulative (h:mm:ss), and the total; "
               "limits from the file's M201/M203/M204/M205, else --profile, else PrusaSlicer's config block, else Marlin's defaults");
  app.add_option("--profile", o.profile,
                 "Machine limits: a key = value file (a PrusaSlicer config.ini works), or the built-in cura or marlin")
      ->type_name("FILE");
  app.add_flag("--no-heat-time", o.no_heat_time, "Leave heating waits (M109, M190) out of the time, as slicers do");
  app.add_option("--svg", o.svg, "Draw layer(s) RANGE from above as SVG (to --svg-out, or standard output)")->type_name("RANGE");
  app.add_option("--svg-sheet", o.svg_sheet, "Draw the layers in RANGE on one SVG page, as a grid")->type_name("RANGE");
  app.add_option("--svg-out", o.svg_out, "Where the SVG goes; with several layers a pattern such as layer-{}.svg")
      ->type_name("PATH");
  app.add_flag("--no-travel", o.no_travel, "Leave travel moves out of the pictures");
  app.add_option("--svg-size", o.svg_size, "Size of a layer's picture in pixels (default 800)")
      ->type_name("PX")
      ->check(CLI::Range(50.0, 20000.0));
  tool.check([&] {
    using gcode::cli::UsageError;
    if (o.io.in_place && !o.cutting()) throw UsageError("--in-place goes with --extract or --z-range");
    if (!o.io.output.empty() && !o.cutting()) throw UsageError("-o goes with --extract or --z-range");
    if (o.cutting() && (o.json || o.where > 0)) throw UsageError("cutting does not combine with --json or --where");
    if (!o.svg.empty() && !o.svg_sheet.empty()) throw UsageError("--svg and --svg-sheet exclude each other");
    if (o.pictures() && (o.cutting() || o.json || o.where > 0))
      throw UsageError("pictures do not combine with --extract, --z-range, --json or --where");
    if (!o.svg_out.empty() && !o.pictures()) throw UsageError("--svg-out goes with --svg or --svg-sheet");
    for (const std::string* r : {&o.extract, &o.svg, &o.svg_sheet})
      if (!r->empty()) gcode::LayerRange::parse(*r);
    if (!o.z_range.empty()) gcode::ZRange::parse(o.z_range);
  });
  return tool.run(argc, argv, [&] {
    gcode::Diagnostics diag = tool.diagnostics(o.io);
    return run(o, diag);
  });
}
