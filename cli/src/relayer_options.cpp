#include "gcode/cli/relayer_options.hpp"

#include <CLI/CLI.hpp>

#include <fmt/format.h>

#include <vector>

#include "gcode/cli/filter.hpp"
#include "gcode/cli/seam_options.hpp"
#include "gcode/core/number.hpp"
#include "gcode/transform/layer_index.hpp"

namespace gcode::cli {

namespace {

constexpr const char* kNotePrefix = "gc-relayer: ";

}  // namespace

void add_relayer_options(Tool& tool, RelayerToolOptions& o) {
  CLI::App& app = tool.app();
  tool.add_filter_options(o.io, kOutput | kVerbosity | kLayerMarker | kEMode);
  app.add_option("FILE", o.io.file,
                 "The re-sliced print (--at-z, --at-layer; the old one comes on standard input), or the print to "
                 "resume")
      ->type_name("FILE");
  auto* at_z = app.add_option("--at-z", o.at_z,
                              "Join FILE (the re-sliced print) onto standard input (the old one) above this height")
                   ->type_name("Z")
                   ->check(non_negative());
  auto* at_layer = app.add_option("--at-layer", o.at_layer, "The same after the old file's layer N (first layer = 1)")
                       ->type_name("N")
                       ->check(CLI::PositiveNumber);
  auto* resume_z = app.add_option("--resume-from-z", o.resume_z,
                                  "Resume FILE on a part measured at this height: the first layer above it on")
                       ->type_name("Z")
                       ->check(non_negative());
  auto* candidates = app.add_option("--list-candidates", o.candidates_z,
                                    "Print the layers of FILE nearest a measured height, with their Z")
                         ->type_name("Z")
                         ->check(non_negative());
  app.add_option("--resume-lift", o.resume_lift,
                 "--resume-from-z: lift the nozzle off the part by this much before declaring Z (mm, default 2)")
      ->type_name("MM")
      ->check(non_negative());
  auto* purge = app.add_option("--purge", o.purge, "--resume-from-z: push this much filament away from the part first (mm)")
                    ->type_name("MM")
                    ->check(non_negative());
  app.add_option("--purge-speed", o.purge_speed, "Speed of the purge (mm/s of filament, default 3)")
      ->type_name("MM/S")
      ->check(positive());
  app.add_option("--purge-at", o.purge_at, "Where to purge (default: 5 mm in from the bed's front left corner)")
      ->type_name("X,Y");
  add_seam_options(tool, o.seam);
  tool.check([&o, at_z, at_layer, resume_z, candidates, purge] {
    int modes = static_cast<int>(at_z->count() + at_layer->count() + resume_z->count() + candidates->count());
    if (modes != 1)
      throw UsageError("give one of --at-z, --at-layer, --resume-from-z or --list-candidates");
    if (o.io.file.empty() || o.io.file == "-")
      throw UsageError(resume_z->count() + candidates->count() > 0
                           ? "give the print's FILE (it is read by layer, not from standard input)"
                           : "give the new FILE (the old print comes on standard input)");
    if (purge->count() > 0 && resume_z->count() == 0) throw UsageError("--purge goes with --resume-from-z");
    o.seam.validate();
  });
}

RelayerPlan::Options join_plan_options(const RelayerToolOptions& o) {
  RelayerPlan::Options ro;
  ro.at_z = o.at_z;
  ro.at_layer = o.at_layer;
  ro.z_decimals = 3;
  ro.note_prefix = kNotePrefix;
  return ro;
}

ResumePlan::Options resume_plan_options(const RelayerToolOptions& o) {
  ResumePlan::Options ro;
  ro.z = *o.resume_z;
  ro.lift = o.resume_lift;
  ro.z_speed = o.seam.z_speed;
  ro.travel_speed = o.seam.travel_speed;
  ro.purge = o.purge;
  ro.purge_speed = o.purge_speed;
  if (!o.purge_at.empty()) {
    std::vector<double> xy;
    if (!parse_number_list(o.purge_at, xy) || xy.size() != 2)
      throw UsageError("--purge-at: expected X,Y, not '" + o.purge_at + "'");
    ro.purge_at_given = true;
    ro.purge_x = xy[0];
    ro.purge_y = xy[1];
  }
  ro.note_prefix = kNotePrefix;
  return ro;
}

std::string layer_candidates_text(const RelayerToolOptions& o) {
  InputFile file(o.io.file);
  file.make_seekable();
  const LayerMarkers markers = o.io.markers();  // the index keeps a reference
  LayerIndex index(file.fd(), file.name(), markers);
  const double z = *o.candidates_z;
  Candidates c = layer_candidates(index, z);
  if (c.below == 0 && c.above == 0) throw InputError(file.name() + " has no layers");
  std::string text;
  if (c.below > 0) {
    const LayerInfo& l = index.layer(c.below).info;
    text += fmt::format("layer {}  Z {}  height {}  {} mm below {}: printed\n", l.index, number_string(l.z, 4),
                        number_string(l.height, 4), number_string(z - l.z, 4), number_string(z, 4));
  }
  if (c.above > 0) {
    const LayerInfo& l = index.layer(c.above).info;
    text += fmt::format("layer {}  Z {}  height {}  {} mm above {}: --resume-from-z {} goes on from here\n", l.index,
                        number_string(l.z, 4), number_string(l.height, 4), number_string(l.z - z, 4),
                        number_string(z, 4), number_string(z, 4));
  } else {
    text += fmt::format("no layer above Z {}: the print is complete\n", number_string(z, 4));
  }
  return text;
}

}  // namespace gcode::cli
