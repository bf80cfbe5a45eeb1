#include "gcode/cli/seam_options.hpp"

#include <CLI/CLI.hpp>

#include "gcode/transform/splice.hpp"

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

std::vector<SpliceFile> SpliceFiles::open(const std::vector<std::string>& names, const LayerMarkers& markers) {
  std::vector<SpliceFile> list;
  for (const std::string& name : names) {
    if (name.empty() || name == "-") throw UsageError("--with and --file need a file (standard input is the print)");
    if (files_.count(name) == 0) {
      auto f = std::make_unique<InputFile>(name);
      f->make_seekable();
      indexes_[name] = std::make_unique<LayerIndex>(f->fd(), name, markers);
      files_[name] = std::move(f);
    }
    list.push_back(SpliceFile{name, files_[name]->fd(), indexes_[name].get()});
  }
  return list;
}

PrintArea splice_printer(Filter& run, const std::vector<SpliceFile>& others, SeamOptions& seam, Diagnostics& diag) {
  PrintArea area = run.print_area();
  for (const SpliceFile& f : others) {
    PrintArea theirs;
    scan_file_limits(f.fd, theirs);
    std::string differs = printer_difference(area, theirs, f.name);
    if (!differs.empty()) diag.warn(differs);
    if (f.index != nullptr && !f.index->e_mode_warning().empty()) diag.warn(f.index->e_mode_warning());
  }
  seam.max_z = area.has_max_z ? area.max_z : 0;
  return area;
}

}  // namespace gcode::cli
