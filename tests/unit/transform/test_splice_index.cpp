// LayerIndex (transform/layer_index.hpp): byte ranges and start states per
// layer from one lazy pass, checked against the report stage gc-layers uses
// (LayerTable) and a replay of the file.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <string>

#include "gcode/core/layer_marker.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "gcode/report/layer_table.hpp"
#include "gcode/transform/layer_index.hpp"
#include "test_support.hpp"

TEST_CASE("splice index: every layer's bytes and start state are what gc-layers and a replay say",
          "[splice][index]") {
  for (const char* name : {"pairs/cura_block_0.2_infill20.gcode", "pairs/prusa_block_0.1_infill20.gcode",
                           "slic3r_cube_0.2_abs_reprap_skirt.gcode", "cura_pegs_0.2_rel_fwretract.gcode"}) {
    INFO(name);
    std::string path = gctest::fixture_path(name);
    std::string text = gctest::read_file(path);
    gcode::LayerMarkers markers;
    gcode::LayerTable table;
    gcode::Pipeline pipeline(markers);
    pipeline.add(table);
    pipeline.run_text(text);

    gctest::OpenedFile f(path);
    gcode::LayerIndex index(f.fd(), name, markers);
    index.read_all();
    REQUIRE(index.complete());
    REQUIRE(index.layers() == static_cast<int>(table.layers().size()));
    for (int k = 1; k <= index.layers(); ++k) {
      const gcode::IndexedLayer& l = index.layer(k);
      const gcode::LayerRow& row = table.layers()[static_cast<std::size_t>(k - 1)];
      INFO("layer " << k);
      CHECK(l.info.offset == row.byte_begin);
      CHECK(l.end == row.byte_end);
      CHECK(l.info.z == row.info.z);
      // The state at the layer's first byte: the replay of everything before it.
      gcode::MachineState before = gctest::replay_state(std::string_view(text).substr(0, l.info.offset));
      CHECK(gcode::same_machine(l.before, before));
    }
    CHECK(index.end_code_offset() == (table.has_end_code() && table.end_code().first_line != 0
                                          ? table.end_code().byte_begin
                                          : text.size()));
    CHECK(index.size() == text.size());
    // The descriptor's own offset is never moved (pread).
    CHECK(::lseek(f.fd(), 0, SEEK_CUR) == 0);
  }
}

TEST_CASE("splice index: reads only as far as asked", "[splice][index]") {
  std::string path = gctest::fixture_path("cura_pegs_0.2_rel_fwretract.gcode");  // 1.3 MB
  gctest::OpenedFile f(path);
  gcode::LayerMarkers markers;
  gcode::LayerIndex index(f.fd(), "x", markers);
  REQUIRE(index.reach(3));
  CHECK(index.layers() >= 3);
  CHECK_FALSE(index.complete());
  CHECK(index.size() < gctest::read_file(path).size());
  index.reach_above(2.0, 1);
  CHECK(index.layer(index.layers()).info.z > 2.0);
  CHECK_FALSE(index.complete());
  CHECK_FALSE(index.reach(500));
  CHECK(index.complete());
}

TEST_CASE("splice index: carried settings and retraction at each layer's start", "[splice][index]") {
  std::string path = gctest::fixture_path("pairs/prusa_block_0.2_infill60_220c_k006.gcode");
  gctest::OpenedFile f(path);
  gcode::LayerMarkers markers;
  gcode::LayerIndex index(f.fd(), "x", markers);
  index.read_all();
  using Kind = gcode::CarriedSettings::Kind;
  gcode::StreamPoint first = index.point(1);
  CHECK(first.settings.find(Kind::Hotend, 0)->value == gcode::Fixed::from_int(220));
  CHECK(first.settings.find(Kind::Advance, 0, "M900")->text == "M900 K0.06");
  CHECK(first.settings.find(Kind::Flow, 0)->value == gcode::Fixed::from_int(95));
  CHECK(first.e_mode_set);
  CHECK(first.layer_z == Approx(0.2));
  // PrusaSlicer switches the fan on at layer 2: on from layer 3's start.
  CHECK(index.point(3).settings.find(Kind::Fan, 0)->value == gcode::Fixed::from_int(255));
  // The versions are shared: far fewer than layers.
  int versions = 0;
  for (int k = 1; k <= index.layers(); ++k) versions = std::max(versions, index.layer(k).settings + 1);
  CHECK(versions < index.layers());
}

TEST_CASE("splice index: a file that never sets its E mode is read in the mode its extrusions show",
          "[splice][index][e-mode]") {
  // PrusaSlicer's Sailfish flavour writes relative E with no M83 (its config
  // block says so): read as absolute, every E value would be misplaced.
  std::string path = gctest::fixture_path("prusa_cube_0.2_sailfish_rel_no_emode.gcode");
  gctest::OpenedFile f(path);
  gcode::LayerMarkers markers;
  gcode::LayerIndex index(f.fd(), "part.gcode", markers);
  REQUIRE(index.reach(3));
  CHECK(index.point(3).state.relative_e);
  CHECK(index.e_mode_warning().find("part.gcode never sets the E mode") != std::string::npos);
  CHECK(index.e_mode_warning().find("relative") != std::string::npos);

  // A file that says M82/M83 itself needs no guess.
  gctest::OpenedFile g(gctest::fixture_path("cura_pegs_0.2_rel_fwretract.gcode"));
  gcode::LayerIndex said(g.fd(), "x", markers);
  REQUIRE(said.reach(3));
  CHECK(said.point(3).state.relative_e);
  CHECK(said.e_mode_warning().empty());
}
