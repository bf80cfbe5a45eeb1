// gc-objects: see the objects of a plate, leave some of them out exactly, or
// label them for the firmware (the objects room: lib/include/gcode/objects/).
#include <fmt/format.h>

#include <optional>

#include "gcode/cli/filter.hpp"
#include "gcode/cli/objects_options.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/objects/footprints.hpp"
#include "gcode/objects/label_writer.hpp"
#include "gcode/objects/object_excluder.hpp"
#include "gcode/objects/object_report.hpp"
#include "gcode/objects/object_table.hpp"

namespace {

using gcode::cli::InputError;
using Options = gcode::cli::ObjectsToolOptions;

// The plate's objects: from the labels, else from the footprints.
struct Plate {
  gcode::ObjectTable table;
  gcode::ObjectBlocks blocks;  // footprints: which lines are whose
  std::vector<gcode::FootprintProblem> problems;
  std::vector<bool> cuttable;
};

// `listing`: the times and outlines too (most of the work); `outlines`: those.
Plate read_plate(gcode::cli::Filter& run, bool listing, bool outlines = false) {
  run.input().make_seekable();
  gcode::EstimatorOptions estimate;
  estimate.limits.load_file_config(run.input().fd());
  run.input().rewind();
  std::optional<gcode::ObjectTableStage> table;
  gcode::ObjectTableStage& labels =
      listing ? table.emplace(estimate) : table.emplace(gcode::ObjectTableStage::Untimed{.outlines = outlines});
  run.prepass(labels, [&](const gcode::Pipeline& p) {
    if (p.bytes_read() == 0) throw InputError(run.input().name() + ": empty input");
    labels.name_features(p.tracker());
  });
  Plate plate{labels.table(), {}, {}, std::vector<bool>(labels.table().objects.size(), true)};
  if (!plate.table.objects.empty()) return plate;
  gcode::FootprintStage footprints(estimate);
  run.prepass(footprints);
  plate = {footprints.table(), footprints.blocks(), footprints.problems(), {}};
  for (std::size_t i = 0; i < plate.table.objects.size(); ++i) plate.cuttable.push_back(footprints.cuttable(static_cast<int>(i)));
  return plate;
}

int list(const Options& o, gcode::cli::Filter& run, gcode::Diagnostics& diag) {
  const Plate plate = read_plate(run, true);
  if (plate.table.objects.empty()) throw InputError(run.input().name() + ": no objects found (no labels, no extrusion)");
  for (const std::string& p : gcode::describe(plate.problems)) diag.warn(p);
  std::string text;
  if (o.json) {
    text = gcode::object_table_json(plate.table);
  } else if (o.svg) {
    const gcode::PrintArea printer = run.print_area();
    text = gcode::object_table_svg(plate.table, printer.has_bed ? printer.bed.outline() : gcode::Polygon{});
  } else {
    text = gcode::object_table_text(plate.table, run.input().name());
  }
  gcode::cli::write_output_file(o.io.output, [&](gcode::OutputBuffer& out) { out.write(text); });
  return 0;
}

int exclude(const Options& o, gcode::cli::Filter& run, gcode::Diagnostics& diag) {
  const Plate plate = read_plate(run, false);
  const std::vector<int> chosen = gcode::cli::chosen_objects(plate.table, o.exclude, run.input().name());
  std::string names;
  for (int i : chosen) {
    const std::string& name = plate.table.objects[static_cast<std::size_t>(i)].name;
    if (!plate.cuttable[static_cast<std::size_t>(i)])
      throw InputError(fmt::format("{} cannot be cut: its extrusions are not all on its footprint ({})", name,
                                   fmt::join(gcode::describe(plate.problems, 3), "; ")));
    names += (names.empty() ? "" : ", ") + name;
  }
  gcode::ExcludeOptions options;
  options.note = "; gc-objects: back on the path after left-out objects";
  gcode::ObjectExcluder excluder(run.pipeline().precision(), options);
  if (!plate.blocks.blocks.empty()) excluder.use_blocks(&plate.blocks);
  for (int i : chosen) excluder.exclude(i, o.from_layer);
  run.add(excluder);
  run.write();
  diag.info(fmt::format("left out {} ({} moves, {} extrusions)", names, excluder.dropped_lines(), excluder.dropped_extrusions()));
  return 0;
}

int label(const Options& o, gcode::cli::Filter& run, gcode::Diagnostics& diag) {
  const Plate plate = read_plate(run, false, true);
  const gcode::ObjectTable& table = plate.table;
  if (table.objects.empty()) throw InputError(run.input().name() + ": no objects found (no labels, no extrusion)");
  if (!plate.blocks.blocks.empty()) throw InputError(run.input().name() + ": no object labels to follow (objects from footprints)");
  if (table.dialect == gcode::LabelDialect::Klipper || table.dialect == gcode::LabelDialect::Marlin)
    throw InputError(fmt::format("{} has firmware labels already ({})", run.input().name(), gcode::dialect_name(table.dialect)));
  gcode::LabelWriter writer(table, o.label == "klipper" ? gcode::FirmwareLabels::Klipper : gcode::FirmwareLabels::Marlin);
  run.add(writer);
  run.write();
  diag.info(fmt::format("labelled {} objects for {}", table.objects.size(), o.label));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return gcode::cli::run_filter(
      argc, argv, "gc-objects",
      "gc-objects: list the objects of a plate (id, name, layers, box, filament, time), draw them, or leave\n"
      "some of them out of the G-code exactly: the other objects' lines byte for byte, the nozzle primed as\n"
      "in the input before each kept extrusion, the travel straight to the next kept object.\n"
      "Objects come from the slicer's labels (PrusaSlicer, SuperSlicer, Slic3r, Cura, ideaMaker, Bambu\n"
      "Studio, OrcaSlicer, M486, Klipper's EXCLUDE_OBJECT), else from their footprints on the first layer.\n"
      "  gc-objects plate.gcode                       the table\n"
      "  gc-objects --exclude 3,pegs.stl_7 plate.gcode -o rest.gcode\n"
      "  gc-objects --label klipper plate.gcode -o labelled.gcode",
      gcode::cli::add_objects_options, [](Options& o, gcode::Diagnostics& diag) {
        gcode::cli::Filter run(o.io);
        if (!o.exclude.empty()) return exclude(o, run, diag);
        if (!o.label.empty()) return label(o, run, diag);
        return list(o, run, diag);
      });
}
