#include "gcode/cli/objects_options.hpp"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>

namespace gcode::cli {

void add_objects_options(Tool& tool, ObjectsToolOptions& o) {
  CLI::App& app = tool.app();
  tool.add_filter_options(o.io);
  auto* json = app.add_flag("--json", o.json, "List the objects as JSON (id, name, bbox, polygon, layers, filament, time, source)");
  auto* svg = app.add_flag("--svg", o.svg, "Draw the plate as SVG: each object's outline, numbered with its id")->excludes(json);
  auto* exclude = app.add_option("--exclude", o.exclude, "Leave these objects out (ids or names, comma-separated): G-code out")
                      ->type_name("ID[,ID...]")
                      ->delimiter(',')
                      ->allow_extra_args(false)
                      ->excludes(json)
                      ->excludes(svg);
  app.add_option("--from-layer", o.from_layer, "With --exclude: leave them out from layer N on (a part came loose there)")
      ->type_name("N")
      ->check(CLI::PositiveNumber)
      ->needs(exclude);
  app.add_option("--label", o.label, "Write firmware labels (Klipper's EXCLUDE_OBJECT_*, Marlin's M486) for the objects")
      ->type_name("klipper|marlin")
      ->check(CLI::IsMember({"klipper", "marlin"}))
      ->excludes(json)
      ->excludes(svg)
      ->excludes(exclude);
  tool.check([&o] {
    if (o.io.in_place && !o.filtering()) throw UsageError("-i needs --exclude or --label (a listing does not change the file)");
  });
}

namespace {

std::string listing(const ObjectTable& table) {
  std::string s;
  for (const PlateObject& o : table.objects) s += fmt::format("\n  {}  {}", o.id, o.name);
  return s;
}

}  // namespace

std::vector<int> chosen_objects(const ObjectTable& table, const std::vector<std::string>& wanted, const std::string& file) {
  if (table.objects.empty()) throw InputError(file + ": no objects found (no labels and no separate footprints)");
  std::vector<int> chosen;
  std::vector<std::string> unknown;
  for (const std::string& w : wanted) {
    const int i = table.find(w);
    if (i < 0) {
      unknown.push_back(w);
    } else if (std::find(chosen.begin(), chosen.end(), i) == chosen.end()) {
      chosen.push_back(i);
    }
  }
  if (!unknown.empty())
    throw UsageError(fmt::format("no object '{}' in {}; its objects (id  name):{}", fmt::join(unknown, "', '"), file, listing(table)));
  if (table.objects.size() == 1)
    throw InputError(fmt::format("{} has one object ({}): leaving it out leaves nothing to print", file, table.objects[0].name));
  if (chosen.size() == table.objects.size())
    throw InputError(fmt::format("leaving out all {} objects of {} leaves nothing to print (that is a cancel)", chosen.size(), file));
  return chosen;
}

}  // namespace gcode::cli
