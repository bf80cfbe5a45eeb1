#pragma once
// gc-objects' listings of an ObjectTable: the text table, the JSON (the
// schema of gc-objects(1)), and the plate as an SVG picture with each
// object's outline and its id.
#include <string>

#include "gcode/core/geometry.hpp"
#include "gcode/objects/object_table.hpp"

namespace gcode {

std::string object_table_text(const ObjectTable& table, const std::string& file_name);
std::string object_table_json(const ObjectTable& table);
// `bed`: the bed's outline, or empty (the picture fits the objects).
std::string object_table_svg(const ObjectTable& table, const Polygon& bed, int size_px = 800);
// The source as the listings name it: "labels" or "footprint".
const char* source_name(ObjectSource s);

}  // namespace gcode
