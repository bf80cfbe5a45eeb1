// gc-layers: see a G-code file by layer, and cut it by layer.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cstdio>
#include <optional>

#include "gcode/diagnostics.hpp"
#include "gcode/layer_extract.hpp"
#include "gcode/layer_range.hpp"
#include "gcode/layer_report.hpp"
#include "gcode/layer_table.hpp"
#include "gcode/layer_tracker.hpp"
#include "gcode/line_reader.hpp"
#include "gcode/output_buffer.hpp"
#include "gcode/tool_io.hpp"
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
};

// Feeds the table and, when cutting, the extractor from one tracker pass.
class Collector : public gcode::LayerSink {
 public:
  explicit Collector(gcode::LayerExtractor* extractor) : extractor_(extractor) {}
  void on_layer(const gcode::LayerInfo& layer, const gcode::MachineState& before) override {
    table.on_layer(layer);
    if (extractor_) extractor_->on_layer(layer, before);
  }
  void on_end_code(std::uint64_t line, std::uint64_t offset, const gcode::MachineState& before) override {
    table.on_end_code();
    if (extractor_) extractor_->on_end_code(line, offset, before);
  }
  void on_line(const gcode::TrackedLine& t) override {
    table.on_line(t);
    if (extractor_) extractor_->on_line(t);
  }
  gcode::LayerTable table;

 private:
  gcode::LayerExtractor* extractor_;
};

// One pass over the input; returns the layer count.
int count_layers(gcode::InputFile& input, const gcode::LayerMarkers& markers) {
  struct Counter : gcode::LayerSink {
    void on_line(const gcode::TrackedLine&) override {}
  } counter;
  gcode::LayerTracker tracker(counter, markers);
  gcode::LineReader reader(input.fd());
  gcode::track_all(reader, tracker);
  input.rewind();
  return tracker.layer_count();
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
  gcode::LayerTracker tracker(collector, markers);
  gcode::LineReader reader(input.fd());
  gcode::track_all(reader, tracker);
  check_has_layers(collector, input);
  int layers = static_cast<int>(collector.table.layers().size());

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
