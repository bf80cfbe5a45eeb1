// gc-layers: see a G-code file by layer, and cut it by layer.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cstdio>
#include <optional>

#include "gcode/core/diagnostics.hpp"
#include "gcode/transform/layer_extract.hpp"
#include "gcode/core/layer_range.hpp"
#include "gcode/report/layer_report.hpp"
#include "gcode/report/layer_svg.hpp"
#include "gcode/report/layer_table.hpp"
#include "gcode/report/layer_time.hpp"
#include "gcode/core/layer_tracker.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/core/output_buffer.hpp"
#include "gcode/core/print_area.hpp"
#include "gcode/cli/io.hpp"
#include "gcode/version.hpp"

namespace {

struct Options {
  std::string file;
  std::string output;
  bool in_place = false;
  bool json = false;
  std::string extract;
  std::string z_range;
  int where = 0;
  std::string layer_marker;
  double density = 1.24;
  double filament_diameter = 1.75;
  bool quiet = false;
  int verbose = 0;
  // --time, --svg, --svg-sheet
  bool time = false;
  std::string profile;
  bool no_heat_time = false;
  std::string svg;
  std::string svg_sheet;
  std::string svg_out;
  bool no_travel = false;
  double svg_size = 800;
};

// Feeds the table and, when cutting, the extractor from one tracker pass.
class Collector : public gcode::LayerSink {
 public:
  explicit Collector(gcode::LayerExtractor* extractor) : extractor_(extractor) {}
  void on_layer(const gcode::LayerInfo& layer, const gcode::MachineState& before) override {
    table.on_layer(layer);
    if (extractor_) extractor_->on_layer(layer, before);
    if (drawer) drawer->on_layer(layer);
  }
  void on_end_code(std::uint64_t line, std::uint64_t offset, const gcode::MachineState& before) override {
    table.on_end_code();
    if (extractor_) extractor_->on_end_code(line, offset, before);
  }
  void on_line(const gcode::TrackedLine& t) override {
    table.on_line(t);
    if (extractor_) extractor_->on_line(t);
    if (timer) timer->on_line(t);
    if (drawer) drawer->on_line(t);
  }
  gcode::LayerTable table;
  gcode::LayerTimer* timer = nullptr;    // --time, --svg
  gcode::LayerDrawer* drawer = nullptr;  // --svg, --svg-sheet

 private:
  gcode::LayerExtractor* extractor_;
};

// One pass over the input, then back to its start; returns the layer count.
int count_layers(gcode::InputFile& input, const gcode::LayerMarkers& markers) {
  gcode::LineReader reader(input.fd());
  int layers = gcode::count_layers(reader, markers);
  input.rewind();
  return layers;
}

// --svg / --svg-sheet: the pictures, to the path(s) of --svg-out (or stdout).
int write_pictures(const Options& o, gcode::LayerDrawer& drawer, const gcode::LayerTimes& times,
                   const gcode::LayerTracker& tracker, const gcode::InputFile& input, const gcode::LayerRange& range,
                   int layers) {
  std::vector<gcode::LayerDrawing>& drawings = drawer.drawings();
  if (range.highest_named() > layers)
    throw std::runtime_error(fmt::format("layer {} does not exist: {} has {} layers", range.highest_named(),
                                         input.name(), layers));
  if (drawings.empty()) throw std::runtime_error("no layer matches the selection");
  gcode::SvgOptions svg;
  svg.travel = !o.no_travel;
  svg.size_px = o.svg_size;
  for (int i = 0; i < tracker.feature_count(); ++i) svg.feature_names.push_back(tracker.feature_name(i));
  gcode::PrintArea printer;
  if (gcode::scan_file_limits(input.fd(), printer) && printer.has_bed)
    svg.bed = {{printer.bed.min_x, printer.bed.min_y}, {printer.bed.max_x, printer.bed.min_y},
               {printer.bed.max_x, printer.bed.max_y}, {printer.bed.min_x, printer.bed.max_y}};
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
  } else {
    if (drawings.size() > 1 && !gcode::has_layer_placeholder(o.svg_out))
      throw std::runtime_error("several layers selected: give --svg-out a pattern such as layer-{}.svg");
    for (const gcode::LayerDrawing& d : drawings) write(gcode::expand_layer_pattern(o.svg_out, d.layer), gcode::layer_svg(d, svg));
  }
  return 0;
}

void check_has_layers(const Collector& c, const gcode::InputFile& input) {
  if (c.table.total_bytes() == 0) throw std::runtime_error(input.name() + ": empty input");
  if (c.table.layers().empty())
    throw std::runtime_error(input.name() + ": no extrusion found (is this a print file?)");
}

int run(const Options& o) {
  gcode::Diagnostics diag("gc-layers", o.quiet ? -1 : o.verbose);
  gcode::LayerMarkers markers = o.layer_marker.empty() ? gcode::LayerMarkers() : gcode::LayerMarkers(o.layer_marker);
  gcode::InputFile input(o.file);
  bool cutting = !o.extract.empty() || !o.z_range.empty();
  std::optional<gcode::LayerRange> range;
  std::optional<gcode::ZRange> zr;
  if (!o.extract.empty()) range = gcode::LayerRange::parse(o.extract);
  if (!o.z_range.empty()) zr = gcode::ZRange::parse(o.z_range);

  int total = 0;
  if (range && range->needs_total()) {
    input.make_seekable();
    total = count_layers(input, markers);
  }
  std::optional<gcode::LayerRange> picture_range;
  if (!o.svg.empty() || !o.svg_sheet.empty()) {
    picture_range = gcode::LayerRange::parse(o.svg.empty() ? o.svg_sheet : o.svg);
    if (picture_range->needs_total() && total == 0) {
      input.make_seekable();
      total = count_layers(input, markers);
    }
  }
  std::optional<gcode::LayerTimer> timer;
  if (o.time || picture_range) {
    gcode::EstimatorOptions estimate;
    estimate.heat_time = !o.no_heat_time;
    estimate.limits.load_file_config(input.fd());
    if (!o.profile.empty()) estimate.limits.load_profile(o.profile);
    timer.emplace(estimate);
  }
  std::optional<gcode::LayerDrawer> drawer;
  if (picture_range)
    drawer.emplace([&](int layer) { return picture_range->contains(layer, total); }, o.filament_diameter);

  std::optional<gcode::OutputFile> out_file;
  std::optional<gcode::OutputBuffer> out;
  std::optional<gcode::LayerExtractor> extractor;
  if (cutting) {
    out_file.emplace(o.output, o.in_place ? o.file : std::string());
    out.emplace(out_file->fd());
    extractor.emplace(*out, [&](const gcode::LayerInfo& l) {
      return (!range || range->contains(l.index, total)) && (!zr || zr->contains(l.z));
    });
  }
  Collector collector(extractor ? &*extractor : nullptr);
  if (timer) collector.timer = &*timer;
  if (drawer) collector.drawer = &*drawer;
  gcode::LayerTracker tracker(collector, markers);
  gcode::LineReader reader(input.fd());
  gcode::track_all(reader, tracker);
  check_has_layers(collector, input);
  int layers = static_cast<int>(collector.table.layers().size());
  if (timer) {
    timer->finish();
    for (const std::string& line : timer->estimator().limits().describe()) diag.info(line);
  }
  if (drawer) {
    drawer->finish();
    return write_pictures(o, *drawer, timer->times(), tracker, input, *picture_range, layers);
  }

  if (cutting) {
    if (range && range->highest_named() > layers)
      throw std::runtime_error(fmt::format("layer {} does not exist: {} has {} layers", range->highest_named(),
                                           input.name(), layers));
    if (extractor->layers_written() == 0) throw std::runtime_error("no layer matches the selection");
    out->flush();
    out_file->commit();
    diag.info(fmt::format("wrote {} of {} layers", extractor->layers_written(), layers));
    return 0;
  }
  if (o.where > 0) {
    if (o.where > layers)
      throw std::runtime_error(fmt::format("layer {} does not exist: {} has {} layers", o.where, input.name(), layers));
    const gcode::LayerRow& r = collector.table.layers()[static_cast<std::size_t>(o.where - 1)];
    fmt::print("{} {} {} {}\n", r.first_line, r.last_line, r.byte_begin, r.byte_end);
    return 0;
  }
  gcode::ReportOptions report{input.name(), o.density, o.filament_diameter, tracker.mode()};
  if (timer) report.times = &timer->times();
  std::string text = o.json ? gcode::layer_table_json(collector.table, tracker, report)
                            : gcode::layer_table_text(collector.table, tracker, report);
  gcode::OutputBuffer stdout_buffer(1);
  stdout_buffer.write(text);
  stdout_buffer.flush();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{
      "gc-layers: show a G-code file layer by layer (lines, bytes, Z, filament, features), or cut it by layer.\n"
      "Layers come from slicer markers (Cura, PrusaSlicer, Slic3r, Orca, Simplify3D) or, in unmarked files,\n"
      "from the Z of extrusions. The first printed layer is 1.",
      "gc-layers"};
  app.add_option("FILE", o.file, "G-code file; - or absent: standard input");
  app.add_flag("--json", o.json, "Print the table as JSON (schema gc-layers/1, see the man page)");
  app.add_option("--extract", o.extract,
                 "Write start code, the layers in RANGE and end code as printable G-code "
                 "(RANGE: 5, 5-9, 5-, -3 for the last three, 5,7,9-12)")
      ->type_name("RANGE");
  app.add_option("--z-range", o.z_range, "Write the layers whose Z lies in Z1:Z2 (either side may be empty)")
      ->type_name("Z1:Z2");
  app.add_option("--where", o.where, "Print first line, last line, first byte and end byte of layer N")
      ->type_name("N")
      ->check(CLI::PositiveNumber);
  app.add_option("-o,--output", o.output, "Write G-code to FILE instead of standard output")->type_name("FILE");
  app.add_flag("-i,--in-place", o.in_place, "Rewrite FILE in place (atomically) with the extract");
  app.add_option("--layer-marker", o.layer_marker,
                 "RE2 pattern that marks a layer start in a comment (first group: the slicer's number)")
      ->type_name("REGEX");
  app.add_option("--density", o.density, "Filament density in g/cm3 for the mass (default PLA 1.24)")
      ->check(CLI::PositiveNumber);
  app.add_option("--filament-diameter", o.filament_diameter, "Filament diameter in mm (default 1.75)")
      ->check(CLI::PositiveNumber);
  app.add_flag("--time", o.time,
               "Add the estimated print time per layer and cumulative (h:mm:ss), and the total; "
               "limits from the file's M201/M203/M204/M205, else --profile, else PrusaSlicer's config block, else Marlin's defaults");
  app.add_option("--profile", o.profile,
                 "Machine limits: a key = value file (a PrusaSlicer config.ini works), or the built-in cura or marlin")
      ->type_name("FILE");
  app.add_flag("--no-heat-time", o.no_heat_time, "Leave heating waits (M109, M190) out of the time, as slicers do");
  app.add_option("--svg", o.svg, "Draw layer(s) RANGE from above as SVG (to --svg-out, or standard output)")
      ->type_name("RANGE");
  app.add_option("--svg-sheet", o.svg_sheet, "Draw the layers in RANGE on one SVG page, as a grid")->type_name("RANGE");
  app.add_option("--svg-out", o.svg_out, "Where the SVG goes; with several layers a pattern such as layer-{}.svg")
      ->type_name("PATH");
  app.add_flag("--no-travel", o.no_travel, "Leave travel moves out of the pictures");
  app.add_option("--svg-size", o.svg_size, "Size of a layer's picture in pixels (default 800)")
      ->type_name("PX")
      ->check(CLI::Range(50.0, 20000.0));
  app.add_flag("-q,--quiet", o.quiet, "Only errors on standard error");
  app.add_flag("-v,--verbose", o.verbose, "More messages on standard error");
  app.set_version_flag("--version", std::string("gc-layers ") + gcode::kVersion);
  try {
    app.parse(argc, argv);
    if (o.in_place && (o.file.empty() || o.file == "-")) throw CLI::ValidationError("-i", "--in-place needs a FILE");
    if (o.in_place && o.extract.empty() && o.z_range.empty())
      throw CLI::ValidationError("-i", "--in-place goes with --extract or --z-range");
    if ((!o.extract.empty() || !o.z_range.empty()) && (o.json || o.where > 0))
      throw CLI::ValidationError("--extract", "cutting does not combine with --json or --where");
    if (o.in_place && !o.output.empty()) throw CLI::ValidationError("-o", "-o and -i exclude each other");
    if (!o.extract.empty()) gcode::LayerRange::parse(o.extract);
    bool pictures = !o.svg.empty() || !o.svg_sheet.empty();
    if (!o.svg.empty() && !o.svg_sheet.empty()) throw CLI::ValidationError("--svg", "--svg and --svg-sheet exclude each other");
    if (pictures && (!o.extract.empty() || !o.z_range.empty() || o.json || o.where > 0))
      throw CLI::ValidationError("--svg", "pictures do not combine with --extract, --z-range, --json or --where");
    if (!o.svg_out.empty() && !pictures) throw CLI::ValidationError("--svg-out", "--svg-out goes with --svg or --svg-sheet");
    if (!o.svg.empty()) gcode::LayerRange::parse(o.svg);
    if (!o.svg_sheet.empty()) gcode::LayerRange::parse(o.svg_sheet);
    if (!o.z_range.empty()) gcode::ZRange::parse(o.z_range);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "gc-layers: %s\n", e.what());
    return 2;
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  return gcode::run_tool("gc-layers", [&] { return run(o); });
}
