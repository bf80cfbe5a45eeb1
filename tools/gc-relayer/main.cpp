// gc-relayer: continue a print with a re-sliced file from a height, or resume
// a failed print from a height (the splice of lib/transform/splice.hpp with
// the rules of lib/transform/relayer.hpp).
#include <fmt/format.h>

#include <optional>

#include "gcode/cli/filter.hpp"
#include "gcode/cli/seam_options.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/core/number.hpp"
#include "gcode/transform/relayer.hpp"
#include "gcode/transform/splice.hpp"

namespace {

using gcode::cli::InputError;
using gcode::cli::UsageError;

struct Options {
  gcode::cli::FilterOptions io;
  gcode::SeamOptions seam;
  std::optional<double> at_z;
  int at_layer = 0;
  std::optional<double> resume_z;
  std::optional<double> candidates_z;
  double resume_lift = 2;
  double purge = 0;
  double purge_speed = 3;
  std::string purge_at;
};

std::string mm(double v) {
  char b[gcode::kMaxNumberChars];
  return std::string(gcode::number_text(v, 4, b));
}

// Messages that report what was done: on standard error unless -q.
void say(const Options& o, const std::vector<std::string>& lines) {
  if (o.io.verbosity() < 0) return;
  for (const std::string& l : lines) fmt::print(stderr, "gc-relayer: {}\n", l);
}

int list_candidates(const Options& o) {
  gcode::InputFile file(o.io.file);
  file.make_seekable();
  const gcode::LayerMarkers markers = o.io.markers();  // the index keeps a reference
  gcode::LayerIndex index(file.fd(), file.name(), markers);
  gcode::Candidates c = gcode::layer_candidates(index, *o.candidates_z);
  if (c.below == 0 && c.above == 0) throw InputError(file.name() + " has no layers");
  const double z = *o.candidates_z;
  if (c.below > 0) {
    const gcode::LayerInfo& l = index.layer(c.below).info;
    fmt::print("layer {}  Z {}  height {}  {} mm below {}: printed\n", l.index, mm(l.z), mm(l.height), mm(z - l.z),
               mm(z));
  }
  if (c.above > 0) {
    const gcode::LayerInfo& l = index.layer(c.above).info;
    fmt::print("layer {}  Z {}  height {}  {} mm above {}: --resume-from-z {} goes on from here\n", l.index, mm(l.z),
               mm(l.height), mm(l.z - z), mm(z), mm(z));
  } else {
    fmt::print("no layer above Z {}: the print is complete\n", mm(z));
  }
  return 0;
}

int join(const Options& o, gcode::Diagnostics& diag) {
  // The new file is FILE; the old one comes on standard input.
  gcode::cli::FilterOptions old_io = o.io;
  old_io.file = "-";
  gcode::cli::Filter run(old_io);
  gcode::InputFile next_file(o.io.file);
  next_file.make_seekable();
  gcode::LayerIndex next(next_file.fd(), next_file.name(), run.markers());
  gcode::PrintArea area = run.print_area(), theirs;
  gcode::scan_file_limits(next_file.fd(), theirs);
  std::string differs = gcode::printer_difference(area, theirs, next_file.name());
  if (!differs.empty()) diag.warn(differs);
  gcode::SeamOptions seam = o.seam;
  seam.max_z = area.has_max_z ? area.max_z : 0;
  gcode::RelayerPlan::Options ro;
  ro.at_z = o.at_z;
  ro.at_layer = o.at_layer;
  ro.z_decimals = 3;
  ro.note_prefix = "gc-relayer: ";
  gcode::RelayerPlan plan(next, ro, &diag);
  gcode::SpliceStage splice(plan, run.pipeline().precision(), seam, &diag);
  splice.set_downstream_reads(false);  // the writer is all that follows
  run.add(splice);
  // Once the new file has taken over, the rest of the old one is not read.
  run.stop_when([&] { return splice.left(); });
  run.write([&] {
    if (!plan.joined()) throw InputError("the input has no layers");
  });
  say(o, plan.report());
  return 0;
}

int resume(const Options& o, gcode::Diagnostics& diag) {
  gcode::cli::Filter run(o.io);
  gcode::ResumePlan::Options ro;
  ro.z = *o.resume_z;
  ro.lift = o.resume_lift;
  ro.z_speed = o.seam.z_speed;
  ro.travel_speed = o.seam.travel_speed;
  ro.purge = o.purge;
  ro.purge_speed = o.purge_speed;
  if (!o.purge_at.empty()) {
    std::vector<double> xy;
    if (!gcode::parse_number_list(o.purge_at, xy) || xy.size() != 2)
      throw UsageError("--purge-at: expected X,Y, not '" + o.purge_at + "'");
    ro.purge_at_given = true;
    ro.purge_x = xy[0];
    ro.purge_y = xy[1];
  }
  ro.area = run.print_area();
  ro.note_prefix = "gc-relayer: ";
  gcode::SeamOptions seam = o.seam;
  seam.max_z = ro.area.has_max_z ? ro.area.max_z : 0;
  gcode::ResumePlan plan(ro, &diag);
  gcode::SpliceStage splice(plan, run.pipeline().precision(), seam, &diag);
  run.add(splice);
  run.write([&] {
    if (!plan.resumed()) throw InputError("the file has no layers");
  });
  say(o, plan.report());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  gcode::cli::Tool tool(
      "gc-relayer",
      "gc-relayer: continue a print with a re-sliced file, or resume a failed print from a height.\n"
      "  gc-relayer --at-z 12 dense.gcode < part.gcode > joined.gcode\n"
      "      part.gcode up to its last layer at or below Z 12, then dense.gcode from the first layer above what\n"
      "      was printed (different layer heights: layers already covered are left out, a missing height is\n"
      "      printed first with the next layer's paths, extrusion scaled). dense.gcode's start code is left\n"
      "      out except its temperatures, fan, flow and pressure advance; its end code is kept.\n"
      "  gc-relayer --resume-from-z 12.3 part.gcode > resume.gcode\n"
      "      after a power cut: heat, lift, declare Z, home X and Y only, then part.gcode from the first\n"
      "      layer above Z 12.3. --list-candidates 12.3 part.gcode shows the layers nearest a measured height.\n"
      "Every travel across a seam goes above everything printed so far.");
  CLI::App& app = tool.app();
  tool.add_filter_options(o.io, gcode::cli::kOutput | gcode::cli::kVerbosity | gcode::cli::kLayerMarker | gcode::cli::kEMode);
  app.add_option("FILE", o.io.file,
                 "The re-sliced print (--at-z, --at-layer; the old one comes on standard input), or the print to "
                 "resume")
      ->type_name("FILE");
  auto* at_z = app.add_option("--at-z", o.at_z,
                              "Join FILE (the re-sliced print) onto standard input (the old one) above this height")
                   ->type_name("Z")
                   ->check(gcode::cli::non_negative());
  auto* at_layer = app.add_option("--at-layer", o.at_layer, "The same after the old file's layer N (first layer = 1)")
                       ->type_name("N")
                       ->check(CLI::PositiveNumber);
  auto* resume_z = app.add_option("--resume-from-z", o.resume_z,
                                  "Resume FILE on a part measured at this height: the first layer above it on")
                       ->type_name("Z")
                       ->check(gcode::cli::non_negative());
  auto* candidates = app.add_option("--list-candidates", o.candidates_z,
                                    "Print the layers of FILE nearest a measured height, with their Z")
                         ->type_name("Z")
                         ->check(gcode::cli::non_negative());
  app.add_option("--resume-lift", o.resume_lift,
                 "--resume-from-z: lift the nozzle off the part by this much before declaring Z (mm, default 2)")
      ->type_name("MM")
      ->check(gcode::cli::non_negative());
  auto* purge = app.add_option("--purge", o.purge, "--resume-from-z: push this much filament away from the part first (mm)")
                    ->type_name("MM")
                    ->check(gcode::cli::non_negative());
  app.add_option("--purge-speed", o.purge_speed, "Speed of the purge (mm/s of filament, default 3)")
      ->type_name("MM/S")
      ->check(gcode::cli::positive());
  app.add_option("--purge-at", o.purge_at, "Where to purge (default: 5 mm in from the bed's front left corner)")
      ->type_name("X,Y");
  gcode::cli::add_seam_options(tool, o.seam);
  tool.check([&] {
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

  return tool.run(argc, argv, [&] {
    gcode::Diagnostics diag = tool.diagnostics(o.io);
    if (o.candidates_z) return list_candidates(o);
    if (o.resume_z) return resume(o, diag);
    return join(o, diag);
  });
}
