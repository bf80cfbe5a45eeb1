// procedural/mesh_vase.hpp with shape_gcode.hpp: the test meshes
// (support/mesh/mesh_maker.hpp) as vases, judged by the independent section
// checker (support/mesh/vase_check.hpp): on the model's surface at the middle of
// every bead, Z never falling, nothing but extrusion in the wall, the
// filament of the bead, the wall up to the top, the bottom filled.
#include <catch2/catch.hpp>

#include <string>

#include "gcode/procedural/mesh_vase.hpp"
#include "gcode/procedural/shape_gcode.hpp"
#include "gcode/procedural/stl_reader.hpp"
#include "mesh/mesh_maker.hpp"
#include "mesh/vase_check.hpp"
#include "mesh/vase_judge.hpp"

namespace test_mesh_vase {

using gcode::procedural::ShapeKind;
using gcode::procedural::ShapeOptions;

std::string vase_gcode(const std::string& stl, const ShapeOptions& o, int& layers) {
  const gcode::procedural::ShapePath path =
      gcode::procedural::mesh_vase(gcode::procedural::read_stl(stl, "test.stl"), o, "test.stl");
  std::string text;
  gcode::procedural::write_shape_gcode(path, {}, [&](std::string_view c) { text.append(c); });
  layers = path.layer_count();
  return text;
}

ShapeOptions vase_options(int bottom_layers = 3) {
  ShapeOptions o;
  o.kind = ShapeKind::Vase;
  o.bottom_layers = bottom_layers;
  return o;
}

void judge(const meshtest::VaseCheck& c, int layers, int bottom_layers) {
  CHECK(c.layers == layers);
  CHECK(c.layers == bottom_layers + c.turns);
  meshtest::judge_wall(c);
  if (bottom_layers > 0) meshtest::judge_bottom(c);
}


TEST_CASE("mesh vase: every test mesh on its surface, rising, one bead, filled below", "[shape][mesh]") {
  for (const meshtest::TestMesh& mesh : {meshtest::cylinder(), meshtest::wavy_vase(), meshtest::twisted_prism(),
                                         meshtest::star(), meshtest::sphere_shade()}) {
    INFO(mesh.name);
    int layers = 0;
    const std::string text = vase_gcode(meshtest::binary_stl(mesh), vase_options(), layers);
    const meshtest::VaseCheck c = meshtest::check_vase(text, mesh);
    judge(c, layers, 3);
  }
}

TEST_CASE("mesh vase: a sloppy ASCII export prints as the clean binary does", "[shape][mesh]") {
  const meshtest::TestMesh mesh = meshtest::wavy_vase();
  int layers = 0;
  const std::string text = vase_gcode(meshtest::sloppy_ascii_stl(mesh), vase_options(), layers);
  const meshtest::VaseCheck c = meshtest::check_vase(text, mesh);
  judge(c, layers, 3);
}

}  // namespace test_mesh_vase
