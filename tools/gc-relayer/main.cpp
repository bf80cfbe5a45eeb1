// gc-relayer: continue a print with a re-sliced file from a height, or resume
// a failed print from a height (the splice of lib/transform/splice.hpp with
// the rules of lib/transform/relayer.hpp; the options of cli/relayer_options.hpp).
#include <fmt/format.h>

#include "gcode/cli/filter.hpp"
#include "gcode/cli/relayer_options.hpp"
#include "gcode/cli/seam_options.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/transform/relayer.hpp"
#include "gcode/transform/splice.hpp"

namespace {

using gcode::cli::InputError;
using Options = gcode::cli::RelayerToolOptions;

// Messages that report what was done: on standard error unless -q.
void say(const Options& o, const std::vector<std::string>& lines) {
  if (o.io.verbosity() < 0) return;
  for (const std::string& l : lines) fmt::print(stderr, "gc-relayer: {}\n", l);
}

int join(const Options& o, gcode::Diagnostics& diag) {
  // The new file is FILE; the old one comes on standard input.
  gcode::cli::FilterOptions old_io = o.io;
  // A moved std::string, not `= "-"`: g++ 12 -O3 warns falsely (-Wrestrict, its bug 105329) on the latter.
  old_io.file = std::string("-");
  gcode::cli::Filter run(old_io);
  gcode::cli::SpliceFiles files;
  const std::vector<gcode::SpliceFile> next = files.open({o.io.file}, run.markers());
  gcode::SeamOptions seam = o.seam;
  gcode::cli::splice_printer(run, next, seam, diag);
  gcode::RelayerPlan plan(*next[0].index, gcode::cli::join_plan_options(o), &diag);
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
  gcode::ResumePlan::Options ro = gcode::cli::resume_plan_options(o);
  gcode::SeamOptions seam = o.seam;
  ro.area = gcode::cli::splice_printer(run, {}, seam, diag);
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
  return gcode::cli::run_filter(
      argc, argv, "gc-relayer",
      "gc-relayer: continue a print with a re-sliced file, or resume a failed print from a height.\n"
      "  gc-relayer --at-z 12 dense.gcode < part.gcode > joined.gcode\n"
      "      part.gcode up to its last layer at or below Z 12, then dense.gcode from the first layer above what\n"
      "      was printed (different layer heights: layers already covered are left out, a missing height is\n"
      "      printed first with the next layer's paths, extrusion scaled). dense.gcode's start code is left\n"
      "      out except its temperatures, fan, flow and pressure advance; its end code is kept.\n"
      "  gc-relayer --resume-from-z 12.3 part.gcode > resume.gcode\n"
      "      after a power cut: heat, lift, declare Z, home X and Y only, then part.gcode from the first\n"
      "      layer above Z 12.3. --list-candidates 12.3 part.gcode shows the layers nearest a measured height.\n"
      "Every travel across a seam goes above everything printed so far.",
      gcode::cli::add_relayer_options, [](Options& o, gcode::Diagnostics& diag) {
        if (o.candidates_z) {
          fmt::print("{}", gcode::cli::layer_candidates_text(o));
          return 0;
        }
        return o.resume_z ? resume(o, diag) : join(o, diag);
      });
}
