// gc-subdivide: cut long moves into short pieces so the printer's buffer holds
// only a few millimetres (or milliseconds) of motion, for a fast pause.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "gcode/core/diagnostics.hpp"
#include "gcode/core/layer_range.hpp"
#include "gcode/core/layer_tracker.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/core/output_buffer.hpp"
#include "gcode/transform/subdivide.hpp"
#include "gcode/cli/io.hpp"
#include "gcode/version.hpp"

namespace {

struct Options {
  std::string file;
  std::string output;
  bool in_place = false;
  gcode::SubdivideOptions split;
  bool min_given = false;
  double baud = 0;
  std::string arcs = "split";
  std::string layers;
  std::string z_range;
  std::string types;
  std::string layer_marker;
  bool quiet = false;
  int verbose = 0;
};

// Bytes a sender puts on the wire per line ("N1234 G1 X.. Y.. E..*56\n"), and
// bits per byte on an 8N1 serial link.
constexpr double kBytesPerLine = 30;
constexpr double kBitsPerByte = 10;

class BufferSink : public gcode::TextSink {
 public:
  explicit BufferSink(gcode::OutputBuffer& out) : out_(out) {}
  void write(std::string_view bytes) override { out_.write(bytes); }

 private:
  gcode::OutputBuffer& out_;
};

bool same_name(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
  return true;
}

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) items.push_back(item);
  return items;
}

// Splits only where the user asked: selected layers, heights and features.
class SelectiveSink : public gcode::LayerSink {
 public:
  SelectiveSink(gcode::Subdivider& subdivider, const gcode::LayerTracker* tracker, const Options& o, int total)
      : subdivider_(subdivider), tracker_(tracker), total_(total), types_(split_list(o.types)) {
    if (!o.layers.empty()) range_ = gcode::LayerRange::parse(o.layers);
    if (!o.z_range.empty()) z_range_ = gcode::ZRange::parse(o.z_range);
  }
  void set_tracker(const gcode::LayerTracker* tracker) { tracker_ = tracker; }
  void on_layer(const gcode::LayerInfo& layer, const gcode::MachineState&) override {
    layer_selected_ = (!range_ || range_->contains(layer.index, total_)) && (!z_range_ || z_range_->contains(layer.z));
    if (layer_selected_) ++layers_selected_;
  }
  void on_line(const gcode::TrackedLine& t) override {
    bool selected = true;
    if (range_ || z_range_) selected = t.region == gcode::Region::Layer && layer_selected_;
    if (selected && !types_.empty()) selected = feature_selected(t.feature);
    subdivider_.process(t.raw, t.line, t.move, t.state, selected);
  }
  int layers_selected() const { return layers_selected_; }

 private:
  bool feature_selected(int feature) {
    if (feature < 0) return false;
    if (feature != last_feature_) {
      last_feature_ = feature;
      last_selected_ = false;
      for (const std::string& name : types_)
        if (same_name(name, tracker_->feature_name(feature))) last_selected_ = true;
    }
    return last_selected_;
  }

  gcode::Subdivider& subdivider_;
  const gcode::LayerTracker* tracker_;
  int total_;
  std::optional<gcode::LayerRange> range_;
  std::optional<gcode::ZRange> z_range_;
  std::vector<std::string> types_;
  bool layer_selected_ = false;
  int layers_selected_ = 0;
  int last_feature_ = -1;
  bool last_selected_ = false;
};

int run(const Options& o) {
  gcode::Diagnostics diag("gc-subdivide", o.quiet ? -1 : o.verbose);
  gcode::InputFile input(o.file);
  bool filtered = !o.layers.empty() || !o.z_range.empty() || !o.types.empty();
  gcode::LayerMarkers markers = o.layer_marker.empty() ? gcode::LayerMarkers() : gcode::LayerMarkers(o.layer_marker);
  int total = 0;
  if (!o.layers.empty() && gcode::LayerRange::parse(o.layers).needs_total()) {
    input.make_seekable();
    gcode::LineReader counting(input.fd());
    total = gcode::count_layers(counting, markers);
    input.rewind();
  }

  gcode::OutputFile out_file(o.output, o.in_place ? o.file : std::string());
  gcode::OutputBuffer out(out_file.fd());
  BufferSink sink(out);
  gcode::Subdivider subdivider(o.split, sink, &diag);
  gcode::LineReader reader(input.fd());
  if (filtered) {
    // Layer numbers need the tracker, which hands the lines on in input order.
    SelectiveSink selective(subdivider, nullptr, o, total);
    gcode::LayerTracker tracker(selective, markers);
    selective.set_tracker(&tracker);
    gcode::track_all(reader, tracker);
    if ((!o.layers.empty() || !o.z_range.empty()) && selective.layers_selected() == 0)
      diag.warn(fmt::format("no layer of {} matches the selection; nothing was split", input.name()));
  } else {
    // Nothing to select: the machine state alone says what each line does.
    gcode::MachineState state;
    gcode::RawLine raw;
    while (reader.next(raw)) {
      gcode::Line line = gcode::Line::parse(raw.text);
      gcode::Move move = state.apply(line);
      subdivider.process(raw, line, move, state);
    }
  }
  out.flush();
  out_file.commit();
  const gcode::SubdivideStats& s = subdivider.stats();
  diag.info(fmt::format("{} lines in, {} moves cut into {} pieces ({} arcs), {} bytes out", s.lines, s.moves_split,
                        s.pieces, s.arcs, out.bytes_written()));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{
      "gc-subdivide: cut long moves into short pieces so the printer's buffer holds only a few mm (or ms) of\n"
      "motion and reacts quickly to a pause. Put it just before gc-send:\n"
      "  gc-subdivide --max 0.2 part.gcode | gc-send --port /dev/ttyACM0\n"
      "A move longer than the limit becomes equal pieces; absolute E ends on the input's own value,\n"
      "relative E and G91 pieces sum exactly to the written amount; F and the comment stay on the first\n"
      "piece. Pure Z and E moves, G10/G11 and short moves are left alone; other lines pass byte for byte.",
      "gc-subdivide"};
  app.add_option("FILE", o.file, "G-code file; - or absent: standard input");
  auto* max = app.add_option("--max", o.split.max_length, "Longest piece in mm (the paper's 0.1-0.2)")
                  ->type_name("MM");
  auto* latency = app.add_option("--latency", o.split.latency,
                                 "Seconds of motion the buffer may hold: piece = speed x SECONDS / --buffer")
                      ->type_name("SECONDS");
  max->excludes(latency);
  app.add_option("--buffer", o.split.buffer,
                 "Moves the firmware buffers (default 20: 16 planner blocks + 4 queued commands)")
      ->type_name("N");
  auto* rate = app.add_option("--max-rate", o.split.max_rate,
                              "Never ask for more lines per second than this (pieces get longer if needed)")
                   ->type_name("LINES_PER_S");
  app.add_option("--baud", o.baud, "Set --max-rate from the serial speed: BAUD / 10 bits / 30 bytes per line")
      ->type_name("BAUD")
      ->excludes(rate);
  app.add_option("--min", o.split.min_length,
                 "Shortest piece in mm (default 0.05; the limit never drops below twice this)")
      ->type_name("MM");
  app.add_flag("--travel,!--no-travel", o.split.split_travel, "Split travel moves too (default) or leave them whole");
  app.add_option("--arcs", o.arcs, "G2/G3: split into G1 chords (default) or keep them")
      ->type_name("keep|split")
      ->check(CLI::IsMember({"keep", "split"}));
  app.add_option("--arc-tolerance", o.split.arc_tolerance, "Largest distance of a chord from its arc in mm (0.01)")
      ->type_name("MM");
  app.add_option("--layers", o.layers, "Split only in these layers (5, 5-9, 5-, -3, 5,7,9-12; first layer = 1)")
      ->type_name("RANGE");
  app.add_option("--z-range", o.z_range, "Split only in layers whose Z lies in Z1:Z2 (either side may be empty)")
      ->type_name("Z1:Z2");
  app.add_option("--types", o.types, "Split only these ;TYPE: features, comma-separated (e.g. WALL-OUTER,FILL)")
      ->type_name("LIST");
  app.add_option("--layer-marker", o.layer_marker,
                 "RE2 pattern that marks a layer start in a comment (first group: the slicer's number)")
      ->type_name("REGEX");
  app.add_option("-o,--output", o.output, "Write to FILE instead of standard output")->type_name("FILE");
  app.add_flag("-i,--in-place", o.in_place, "Rewrite FILE in place (atomically)");
  app.add_flag("-q,--quiet", o.quiet, "Only errors on standard error");
  app.add_flag("-v,--verbose", o.verbose, "Also report what was done on standard error");
  app.set_version_flag("--version", std::string("gc-subdivide ") + gcode::kVersion);
  try {
    app.parse(argc, argv);
    if (o.in_place && (o.file.empty() || o.file == "-")) throw CLI::ValidationError("-i", "--in-place needs a FILE");
    if (o.in_place && !o.output.empty()) throw CLI::ValidationError("-o", "-o and -i exclude each other");
    o.min_given = app.count("--min") > 0;
    o.split.split_arcs = o.arcs == "split";
    if (o.baud < 0 || !std::isfinite(o.baud)) throw std::invalid_argument("--baud must be a serial speed above 0");
    if (o.baud > 0) o.split.max_rate = o.baud / kBitsPerByte / kBytesPerLine;
    // The default floor gives way to a small --max; an explicit one does not.
    if (!o.min_given && o.split.max_length > 0 && o.split.max_length < 2 * o.split.min_length)
      o.split.min_length = o.split.max_length / 2;
    o.split.validate();
    if (!o.split.has_limit() && app.count("--arcs") == 0)
      throw std::invalid_argument("give a limit: --max MM or --latency SECONDS (or --arcs split to only linearise arcs)");
    if (!o.layers.empty()) gcode::LayerRange::parse(o.layers);
    if (!o.z_range.empty()) gcode::ZRange::parse(o.z_range);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "gc-subdivide: %s\n", e.what());
    return 2;
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    std::fprintf(stderr, "gc-subdivide: %s (see --help)\n", e.what());
    return 2;
  }
  return gcode::run_tool("gc-subdivide", [&] { return run(o); });
}
