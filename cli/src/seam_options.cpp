#include "gcode/cli/seam_options.hpp"

namespace gcode::cli {

void add_seam_options(Tool& tool, SeamOptions& o) {
  CLI::App& app = tool.app();
  app.add_option("--lift", o.lift, "Travel this far above the highest Z printed at a seam (mm, default 1)")
      ->type_name("MM")
      ->check(non_negative());
  app.add_option("--retract", o.retract,
                 "Retract this much for a seam's travel when nothing is retracted (mm, default 1; 0: never)")
      ->type_name("MM")
      ->check(non_negative());
  app.add_option("--retract-speed", o.retract_speed, "Retract and unretract speed at a seam (mm/s, default 35)")
      ->type_name("MM/S")
      ->check(positive());
  app.add_option("--travel-speed", o.travel_speed, "XY travel speed at a seam (mm/s, default 50)")
      ->type_name("MM/S")
      ->check(positive());
  app.add_option("--z-speed", o.z_speed, "Z speed of a seam's lift and descent (mm/s, default 10)")
      ->type_name("MM/S")
      ->check(positive());
}

}  // namespace gcode::cli
