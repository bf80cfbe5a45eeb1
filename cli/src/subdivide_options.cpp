#include "gcode/cli/subdivide_options.hpp"

#include <CLI/CLI.hpp>

namespace gcode::cli {

namespace {

// Bytes a sender puts on the wire per line ("N1234 G1 X.. Y.. E..*56\n"), and
// bits per byte on an 8N1 serial link.
constexpr double kBytesPerLine = 30;
constexpr double kBitsPerByte = 10;

}  // namespace

void add_subdivide_options(Tool& tool, SubdivideToolOptions& o) {
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
      ->check(positive())
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
  tool.check([&o, min, arcs] {
    o.split.split_arcs = o.arcs == "split";
    if (o.baud > 0) o.split.max_rate = o.baud / kBitsPerByte / kBytesPerLine;
    // The default floor gives way to a small --max; an explicit one does not.
    if (min->count() == 0 && o.split.max_length > 0 && o.split.max_length < 2 * o.split.min_length)
      o.split.min_length = o.split.max_length / 2;
    o.split.validate();
    if (!o.split.has_limit() && arcs->count() == 0)
      throw UsageError("give a limit: --max MM or --latency SECONDS (or --arcs split to only linearise arcs)");
  });
}

}  // namespace gcode::cli
