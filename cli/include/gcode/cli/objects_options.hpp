#pragma once
// gc-objects' options: the listing (table, --json, --svg), --exclude with
// --from-layer, --label; and the objects --exclude names, checked against
// the file's table.
#include <string>
#include <vector>

#include "gcode/cli/tool.hpp"
#include "gcode/objects/object_table.hpp"

namespace gcode::cli {

struct ObjectsToolOptions {
  FilterOptions io;
  bool json = false;
  bool svg = false;
  std::vector<std::string> exclude;  // ids or names
  int from_layer = 0;
  std::string label;                 // "", "klipper" or "marlin"
  bool filtering() const { return !exclude.empty() || !label.empty(); }
};

void add_objects_options(Tool& tool, ObjectsToolOptions& options);

// The objects --exclude names, as indexes into `table`: an unknown name is
// a UsageError listing the file's objects; leaving out every object, or a
// file with one object or none, an InputError.
std::vector<int> chosen_objects(const ObjectTable& table, const std::vector<std::string>& wanted, const std::string& file);

}  // namespace gcode::cli
