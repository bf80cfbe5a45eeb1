// gc-subdivide: cut long moves into short pieces so the printer's buffer holds
// only a few millimetres (or milliseconds) of motion, for a fast pause.
#include <fmt/format.h>

#include <cmath>

#include "gcode/cli/filter.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/transform/subdivide.hpp"

namespace {

// Bytes a sender puts on the wire per line ("N1234 G1 X.. Y.. E..*56\n"), and
// bits per byte on an 8N1 serial link.
constexpr double kBytesPerLine = 30;
constexpr double kBitsPerByte = 10;

struct Options {
  gcode::cli::FilterOptions io;
  gcode::SubdivideOptions split;
  gcode::SelectionText where;
  double baud = 0;
  std::string arcs = "split";
};

}  // namespace

int main(int argc, char** argv) {
  Options o;
  gcode::cli::Tool tool(
      "gc-subdivide",
      "gc-subdivide: cut long moves into short pieces so the printer's buffer holds only a few mm (or ms) of\n"
      "motion and reacts quickly to a pause. Put it just before gc-send:\n"
      "  gc-subdivide --max 0.2 part.gcode | gc-send --port /dev/ttyACM0\n"
      "A move longer than the limit becomes equal pieces; absolute E ends on the input's own value,\n"
      "relative E and G91 pieces sum exactly to the written amount; F and the comment stay on the first\n"
      "piece. Pure Z and E moves, G10/G11 and short moves are left alone; other lines pass byte for byte.");
  CLI::App& app = tool.app();
  tool.add_filter_options(o.io);
  auto* max = app.add_option("--max", o.split.max_length, "Longest piece in mm (the paper's 0.1-0.2)")->type_name("MM");
  auto* latency = app.add_option("--latency", o.split.latency,
                                 "Seconds of motion the buffer may hold: piece = speed x SECONDS / --buffer")
                      ->type_name("SECONDS");
  max->excludes(latency);
  app.add_option("--buffer", o.split.buffer, "Moves the firmware buffers (default 20: 16 planner blocks + 4 queued commands)")
      ->type_name("N");
  auto* rate = app.add_option("--max-rate", o.split.max_rate,
                              "Never ask for more lines per second than this (pieces get longer if needed)")
                   ->type_name("LINES_PER_S");
  app.add_option("--baud", o.baud, "Set --max-rate from the serial speed: BAUD / 10 bits / 30 bytes per line")
      ->type_name("BAUD")
      ->check(gcode::cli::positive())
      ->excludes(rate);
  auto* min = app.add_option("--min", o.split.min_length,
                             "Shortest piece in mm (default 0.05; the limit never drops below twice this)")
                  ->type_name("MM");
  app.add_flag("--travel,!--no-travel", o.split.split_travel, "Split travel moves too (default) or leave them whole");
  auto* arcs = app.add_option("--arcs", o.arcs, "G2/G3: split into G1 chords (default) or keep them")
                   ->type_name("keep|split")
                   ->check(CLI::IsMember({"keep", "split"}));
  app.add_option("--arc-tolerance", o.split.arc_tolerance, "Largest distance of a chord from its arc in mm (0.01)")
      ->type_name("MM");
  tool.add_selection(o.where, "Split only in");
  tool.check([&] {
    o.split.split_arcs = o.arcs == "split";
    if (o.baud > 0) o.split.max_rate = o.baud / kBitsPerByte / kBytesPerLine;
    // The default floor gives way to a small --max; an explicit one does not.
    if (min->count() == 0 && o.split.max_length > 0 && o.split.max_length < 2 * o.split.min_length)
      o.split.min_length = o.split.max_length / 2;
    o.split.validate();
    if (!o.split.has_limit() && arcs->count() == 0)
      throw gcode::cli::UsageError(
          "give a limit: --max MM or --latency SECONDS (or --arcs split to only linearise arcs)");
  });

  return tool.run(argc, argv, [&] {
    gcode::Diagnostics diag = tool.diagnostics(o.io);
    gcode::LayerSelection where;
    // Layer numbers need the layer tracker; without a selection nothing is held back.
    bool selected = !o.where.layers.empty() || !o.where.z_range.empty() || !o.where.types.empty();
    gcode::cli::Filter run(o.io, gcode::PipelineOptions{.layers = selected});
    if (selected) where = run.selection(o.where);
    gcode::Subdivider subdivider(o.split, run.pipeline().precision(), &diag, selected ? &where : nullptr);
    run.add(subdivider);
    run.write([&] { run.check_selection(where, diag, "split"); });
    const gcode::SubdivideStats& s = subdivider.stats();
    diag.info(fmt::format("{} lines in, {} moves cut into {} pieces ({} arcs), {} bytes out", s.lines, s.moves_split,
                          s.pieces, s.arcs, run.output()->bytes_written()));
    return 0;
  });
}
