#include "gcode/procedural/mesh_vase.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "gcode/core/number.hpp"
#include "gcode/procedural/bottom_fill.hpp"
#include "gcode/procedural/mesh_slicer.hpp"
#include "gcode/procedural/spiral_wall.hpp"
#include "gcode/procedural/wall_outline.hpp"

namespace gcode::procedural {

namespace {

std::string mm(double v) { return number_string(v, 3); }

void check_fits(const Box3& b, const ShapeOptions& o, std::string_view name) {
  if (b.min[0] < 0 || b.min[1] < 0 || b.max[0] > o.bed_width || b.max[1] > o.bed_depth)
    throw MeshError(fmt::format("{}: the model ({} x {} mm about {},{}) does not fit on the {} x {} mm bed", name,
                                mm(b.max[0] - b.min[0]), mm(b.max[1] - b.min[1]), mm(o.center_x), mm(o.center_y),
                                mm(o.bed_width), mm(o.bed_depth)));
  if (b.max[2] > o.bed_height)
    throw MeshError(fmt::format("{}: the model is {} mm tall, the printer {} mm", name, mm(b.max[2]), mm(o.bed_height)));
  const double bottom = o.bottom_layers * o.layer_height;
  if (b.max[2] < bottom + o.layer_height)
    throw MeshError(fmt::format("{}: the model is {} mm tall, too low for {} bottom layers and a turn of the wall",
                                name, mm(b.max[2]), o.bottom_layers));
}

std::vector<std::string> parameters(const Mesh& mesh, const Box3& b, const ShapeOptions& o, std::string_view name) {
  return {fmt::format("mesh = {} ({} triangles, {} vertices)", name, mesh.triangles.size(), mesh.vertices.size()),
          fmt::format("scale = {}", number_string(o.scale, 6)),
          fmt::format("model = {} x {} x {} mm", mm(b.max[0] - b.min[0]), mm(b.max[1] - b.min[1]), mm(b.max[2])),
          fmt::format("bottom_layers = {}", o.bottom_layers),
          fmt::format("bed = {} x {} x {} mm", mm(o.bed_width), mm(o.bed_depth), mm(o.bed_height))};
}

}  // namespace

ShapePath mesh_vase(Mesh mesh, const ShapeOptions& options, std::string_view name) {
  ShapeOptions o = options;
  o.validate();
  mesh.place(o.scale, o.center_x, o.center_y);
  const Box3 b = mesh.bounds();
  check_fits(b, o, name);
  LaidPath laid;
  laid.bottom_layers = o.bottom_layers;
  const double base = o.bottom_layers * o.layer_height;
  laid.turns = std::max(1, static_cast<int>(std::ceil((b.max[2] - base) / o.layer_height - 1e-9)));
  laid.pitch = (b.max[2] - base) / laid.turns;
  laid.top = b.max[2];
  laid.box = b.xy();
  laid.parameters = parameters(mesh, b, o, name);

  MeshSlicer slicer(mesh);
  HeightProblems problems;
  bottom_fill(slicer, {o.bottom_layers, o.layer_height, o.line_width, o.tolerance, b.max[2]}, laid.layers, problems);
  Point2 from{b.max[0], (b.min[1] + b.max[1]) / 2};  // a wall without a bottom starts on +X, as the helix
  if (!laid.layers.empty() && !laid.layers.back().points.empty())
    from = {laid.layers.back().points.back().x, laid.layers.back().points.back().y};
  spiral_wall(slicer, {base, laid.pitch, laid.turns, o.line_width, o.tolerance, b.max[2]}, from, laid.layers, problems);
  if (!problems.empty()) throw MeshError(fmt::format("{}: {}", name, problems.message()));

  ShapeLayer& first = laid.layers.front();
  laid.start = first.points.front();
  laid.start.travel = false;
  first.points.erase(first.points.begin());
  return ShapePath(o, std::move(laid));
}

}  // namespace gcode::procedural
