// procedural/shape_gcode.hpp: the program every gc tool reads, E exactly the
// bead on every piece, one layer a turn, no layer change and no retraction
// inside the layers (checked by shape_check.hpp's replay).
#include <catch2/catch.hpp>

#include <string>

#include "gcode/procedural/shape_gcode.hpp"
#include "shape_check.hpp"

using gcode::procedural::ShapeGcodeOptions;
using gcode::procedural::ShapeKind;
using gcode::procedural::ShapeOptions;
using gcode::procedural::ShapePath;

namespace {

struct ShapeWritten {
  std::string text;
  gcode::procedural::ShapeGcodeStats stats;
  int chunks = 0;
};

ShapeWritten write(const ShapePath& path, const ShapeGcodeOptions& g = {}) {
  ShapeWritten w;
  w.stats = gcode::procedural::write_shape_gcode(path, g, [&](std::string_view c) {
    w.text.append(c);
    ++w.chunks;
  });
  return w;
}

}  // namespace

TEST_CASE("every primitive: on its curve, E = the bead on every piece, nothing but extrusion in the layers",
          "[shape]") {
  for (ShapeKind kind : {ShapeKind::Circle, ShapeKind::Spiral, ShapeKind::Helix, ShapeKind::Cylinder,
                         ShapeKind::Polygon, ShapeKind::Cone}) {
    ShapeOptions o;
    o.kind = kind;
    o.diameter = 30;
    o.height = 3;
    const ShapePath path(o);
    const ShapeWritten w = write(path);
    INFO(gcode::procedural::shape_kind_name(kind));
    const shapetest::ShapeCheck c = shapetest::check_shape(w.text, o, path.pitch(), path.turns());
    CHECK(c.pieces == w.stats.moves);
    CHECK(c.worst_chord <= o.tolerance);
    CHECK(c.worst_e <= 0);
    CHECK(c.other_moves == 0);
    CHECK(c.filament == Approx(w.stats.filament).epsilon(1e-9));
    CHECK(w.chunks == path.layer_count() + 2);  // header and start, a layer each, the end
    CHECK(gctest::places_of(w.text).layer.back() == 0);  // the end code after the last layer
  }
}

TEST_CASE("the header: Cura's box and markers, the parameters, the filament it then writes", "[shape]") {
  ShapeOptions o;
  o.kind = ShapeKind::Cone;
  o.height = 2;
  const ShapePath path(o);
  const ShapeWritten w = write(path);
  for (const char* s : {";FLAVOR:Marlin\n", ";MINX:80\n", ";MAXY:140\n", ";MAXZ:2\n", ";LAYER_COUNT:7\n", ";LAYER:6\n",
                        ";  shape = cone\n", ";  top_diameter = 30 mm\n", ";TYPE:WALL-OUTER\n", "M106 S255\n"})
    CHECK(w.text.find(s) != std::string::npos);
  char used[64];
  std::snprintf(used, sizeof used, ";Filament used: %.5fm\n", w.stats.filament / 1000);
  std::string expected = used;
  while (expected[expected.size() - 3] == '0') expected.erase(expected.size() - 3, 1);  // trailing zeros dropped
  CHECK(w.text.find(expected) != std::string::npos);
}

TEST_CASE("given start and end code replace the built-in ones, absolute positions, relative E follow", "[shape]") {
  ShapeOptions o;
  o.kind = ShapeKind::Circle;
  ShapeGcodeOptions g;
  g.start_code = "G28 ; mine";
  g.end_code = "M84 ; mine too";
  g.start_name = "start.gcode";
  const ShapeWritten w = write(ShapePath(o), g);
  CHECK(w.text.find("G28 ; mine\nG90\nM83") != std::string::npos);
  CHECK(w.text.find("M190") == std::string::npos);
  CHECK(w.text.find(";  start = start.gcode\n") != std::string::npos);
  CHECK(w.text.substr(w.text.size() - 15) == "M84 ; mine too\n");
  g.retract_length = 0;
  g.start_code.clear();
  const ShapeWritten plain = write(ShapePath(o), g);
  CHECK(plain.text.find("G1 F2100 E") == std::string::npos);
  const gcode::MachineState end = gctest::replay_state(plain.text);
  CHECK(end.relative_e);
}
