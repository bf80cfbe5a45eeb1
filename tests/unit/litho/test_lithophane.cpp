#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "gcode/litho/lithophane.hpp"
#include "litho_support.hpp"

using gcode::litho::GreyImage;
using gcode::litho::HeightMap;
using gcode::litho::HeightMapOptions;
using gcode::litho::LithoLayer;
using gcode::litho::LithoOptions;
using gcode::litho::LithophanePlanner;
using gcode::litho::LithoShape;
using gcode::litho::PathRole;

using littest::plate;

namespace {

GreyImage flat_grey(int luma) {
  return GreyImage(8, 8, std::vector<std::uint8_t>(64, static_cast<std::uint8_t>(luma)));
}

HeightMapOptions cylinder(double diameter, double height) {
  HeightMapOptions o;
  o.shape = LithoShape::Cylinder;
  o.diameter = diameter;
  o.height = height;
  return o;
}

// The luma that gives thickness t with the default range 0.8..3.0 mm.
int luma_for(double t) { return static_cast<int>(std::lround(255 * (1 - (t - 0.8) / 2.2))); }

std::size_t count_role(const LithoLayer& layer, PathRole role) {
  std::size_t n = 0;
  for (const auto& p : layer.paths) n += p.role == role;
  return n;
}

}  // namespace

TEST_CASE("litho planner: a uniform full thickness plate is exactly filled by a wall loop and three passes", "[litho][lithophane]") {
  const HeightMap map(flat_grey(0), plate(20));  // 3.0 mm everywhere, 20 x 20 mm
  const LithophanePlanner planner(map, LithoOptions{});
  CHECK(planner.layer_count() == 100);
  CHECK(planner.fill_rate() == Approx(15));  // the hot end's melt limit, --max-flow
  CHECK(planner.wall_rate() == Approx(0.45 * 0.2 * 40));
  LithoLayer layer;
  planner.plan_layer(50, layer);
  CHECK(layer.z == Approx(10.2));
  CHECK(layer.sample_z == Approx(10.1));
  // The gap is 3.0 - 2 x 0.45 = 2.1 mm: three passes of 0.7 mm (max pass width 1.0 mm).
  CHECK(layer.stats.max_passes == 3);
  CHECK(count_role(layer, PathRole::Fill) == 3);
  CHECK(count_role(layer, PathRole::Base) == 1);
  CHECK(count_role(layer, PathRole::WallInner) == 0);
  CHECK(count_role(layer, PathRole::WallOuter) == 1);
  CHECK(layer.stats.band_area == Approx(20 * 3.0).epsilon(1e-12));
  CHECK(layer.stats.volume == Approx(20 * 3.0 * 0.2).epsilon(1e-12));
  CHECK(layer.stats.clamped_fast + layer.stats.clamped_slow == 0);
  for (const auto& path : layer.paths)
    for (const auto& piece : path.pieces) {
      if (path.role == PathRole::Fill) {
        REQUIRE(piece.width == Approx(0.7));
        REQUIRE(piece.speed == Approx(15 / (0.7 * 0.2)));  // v = q / (W x H)
      } else {
        REQUIRE(piece.width == Approx(0.45));
        // The outer wall (and its caps) at wall speed, the base bead at q.
        REQUIRE(piece.speed == Approx(path.role == PathRole::Base ? 15 / (0.45 * 0.2) : 40));
      }
    }
  // The wall loop closes on its start; passes sit side by side, 0.7 mm apart.
  const auto& inner = layer.paths[0];
  const auto& outer = layer.paths[1];
  CHECK(outer.start.x == inner.pieces.back().to.x);
  CHECK(outer.pieces.back().to.x == inner.start.x);
  CHECK(outer.pieces.back().to.y == inner.start.y);
  CHECK(layer.paths[3].start.y - layer.paths[2].start.y == Approx(0.7));
}

TEST_CASE("litho planner: a band thinner than two walls is shared by the walls at their extruder rate", "[litho][lithophane]") {
  const HeightMap map(flat_grey(255), plate(20));  // 0.8 mm everywhere
  const LithophanePlanner planner(map, LithoOptions{});
  LithoLayer layer;
  planner.plan_layer(3, layer);
  CHECK(count_role(layer, PathRole::Fill) == 0);
  CHECK(layer.stats.band_area == Approx(20 * 0.8).epsilon(1e-12));
  // Along the plate each wall is 0.4 mm: the outer one faster than 40 mm/s
  // so that the rate stays 3.6 mm3/s, the base bead at q. The base bead is
  // straight and even: one move.
  const auto& inner = layer.paths[0];
  REQUIRE(inner.role == PathRole::Base);
  REQUIRE(inner.pieces.size() == 1);
  CHECK(inner.pieces[0].width == Approx(0.4));
  CHECK(inner.pieces[0].speed == Approx(15 / (0.4 * 0.2)));
  CHECK(inner.pieces[0].to.x - inner.start.x == Approx(20 - 0.45));
  CHECK(layer.paths[1].pieces[1].width == Approx(0.4));  // past the end cap
  CHECK(layer.paths[1].pieces[1].speed == Approx(3.6 / (0.4 * 0.2)));
}

TEST_CASE("litho planner: a gap narrower than the minimum pass gets no pass and the walls close it", "[litho][lithophane]") {
  // 2 x 0.45 + 0.1 = 1.0 mm: a gap of 0.1 mm, under the 0.2 mm minimum.
  const HeightMap map(flat_grey(luma_for(1.0)), plate(20));
  const LithophanePlanner planner(map, LithoOptions{});
  LithoLayer layer;
  planner.plan_layer(10, layer);
  const double t = map.thickness(10, layer.sample_z);
  REQUIRE(t - 0.9 < 0.2);
  CHECK(count_role(layer, PathRole::Fill) == 0);
  CHECK(layer.stats.band_area == Approx(20 * t).epsilon(1e-12));
  CHECK(layer.paths[0].pieces[0].width == Approx(t / 2));
}

TEST_CASE("litho planner: pass counts follow the gap and every layer's strips tile the band", "[litho][lithophane]") {
  // Horizontal gradient: 3.0 mm at the left edge to 0.8 mm at the right.
  const HeightMap map(littest::gradient(64, 32), plate(40));
  const LithophanePlanner planner(map, LithoOptions{});
  LithoLayer layer;
  for (int i = 0; i < planner.layer_count(); i += 7) {
    planner.plan_layer(i, layer);
    double exact = 0;  // trapezoids of 0.001 mm
    for (double s = 0; s < 40; s += 0.001) exact += (map.thickness(s, layer.sample_z) + map.thickness(s + 0.001, layer.sample_z)) / 2 * 0.001;
    REQUIRE(layer.stats.band_area == Approx(exact).epsilon(1e-4));
    REQUIRE(layer.stats.max_passes == 3);
  }
}

TEST_CASE("litho planner: a clamped speed keeps the width and the piece is counted", "[litho][lithophane]") {
  const HeightMap map(flat_grey(0), plate(20));
  LithoOptions slow;
  slow.max_speed = 50;  // the passes want 107 mm/s
  slow.base_wall = true;  // the base as a wall at 40 mm/s, under the limit
  const LithophanePlanner planner(map, slow);
  LithoLayer layer;
  planner.plan_layer(5, layer);
  CHECK(layer.stats.clamped_fast == layer.stats.fill_pieces);
  CHECK(layer.stats.volume == Approx(20 * 3.0 * 0.2).epsilon(1e-12));
  for (const auto& path : layer.paths)
    if (path.role == PathRole::Fill)
      for (const auto& piece : path.pieces) {
        REQUIRE(piece.speed == 50);
        REQUIRE(piece.clamped);
        REQUIRE(piece.width == Approx(0.7));
      }
  LithoOptions fast;
  fast.min_speed = 100;
  fast.max_speed = 300;
  fast.infill_speed = 100;  // q of conventional infill at 100 mm/s: 9 mm3/s
  fast.base_wall = true;
  const LithophanePlanner p2(map, fast);
  p2.plan_layer(5, layer);
  CHECK(layer.stats.clamped_slow == layer.stats.pieces);  // walls (40) and passes (64) both below 100
}

TEST_CASE("litho planner: the first layer runs at the first layer factor of every rate", "[litho][lithophane]") {
  const HeightMap map(flat_grey(0), plate(20));
  const LithophanePlanner planner(map, LithoOptions{});
  LithoLayer first, second;
  planner.plan_layer(0, first);
  planner.plan_layer(1, second);
  REQUIRE(first.paths.size() == second.paths.size());
  for (std::size_t p = 0; p < first.paths.size(); ++p)
    for (std::size_t i = 0; i < first.paths[p].pieces.size(); ++i) {
      REQUIRE(first.paths[p].pieces[i].speed == Approx(second.paths[p].pieces[i].speed / 2));
      REQUIRE(first.paths[p].pieces[i].volume == Approx(second.paths[p].pieces[i].volume));
    }
}

TEST_CASE("litho planner: a cylinder layer is an outer ring an inner ring and closed passes", "[litho][lithophane]") {
  const HeightMap map(flat_grey(0), cylinder(40, 10));
  const LithophanePlanner planner(map, LithoOptions{});
  LithoLayer layer;
  planner.plan_layer(20, layer);
  // 2.1 mm of gap: two passes of 1.0 mm and a base bead 0.1 mm wider, the fewest beads.
  REQUIRE(layer.paths.size() == 4);
  CHECK(layer.paths[0].role == PathRole::WallOuter);
  CHECK(layer.paths[1].role == PathRole::Base);
  const double r = 20;
  CHECK(layer.stats.band_area == Approx(std::numbers::pi * ((r + 3) * (r + 3) - r * r)).epsilon(1e-9));
  for (const auto& path : layer.paths) {
    // A ring ends exactly where it began.
    CHECK(path.pieces.back().to.x == path.start.x);
    CHECK(path.pieces.back().to.y == path.start.y);
  }
  // The outer wall's centre line runs 0.225 mm inside the 3 mm surface.
  const auto& outer = layer.paths[0];
  CHECK(std::hypot(outer.start.x - 110, outer.start.y - 110) == Approx(r + 3 - 0.225));
}

TEST_CASE("litho planner: a cylinder with a varying picture splits its passes into runs where the count changes", "[litho][lithophane]") {
  const HeightMap map(littest::gradient(64, 16), cylinder(30, 5));
  const LithophanePlanner planner(map, LithoOptions{});
  LithoLayer layer;
  planner.plan_layer(10, layer);
  // 2.1 mm of gap at the thickest: two passes and a base bead 0.1 mm wider
  // rather than a third pass, for one change of count fewer.
  CHECK(layer.stats.max_passes == 2);
  double exact = 0;  // polar area of the band, 0.0001 rad steps
  const double r = 15;
  for (double a = 0; a < 2 * std::numbers::pi; a += 1e-4) {
    const double t = map.thickness(a * r, layer.sample_z);
    exact += ((r + t) * (r + t) - r * r) / 2 * 1e-4;
  }
  CHECK(layer.stats.band_area == Approx(exact).epsilon(1e-3));
  CHECK(count_role(layer, PathRole::Fill) > 3);
}

TEST_CASE("litho planner: the base bead widens where that keeps one count of passes along the layer", "[litho][lithophane]") {
  // Stripes 2.5 mm wide of 0.3 mm of gap (one pass only) and 1.05 mm (two
  // passes under the 1.0 mm maximum): one pass all along instead, the base
  // bead 0.05 mm wider in the thick stripes.
  std::vector<std::uint8_t> px(72);
  for (std::size_t i = 0; i < px.size(); ++i)
    px[i] = static_cast<std::uint8_t>(luma_for(i % 9 % 2 == 0 ? 1.2 : 1.95));
  const HeightMap map(GreyImage(9, 8, px), plate(22.5));
  LithoLayer layer;
  const LithophanePlanner planner(map, LithoOptions{});
  planner.plan_layer(10, layer);
  CHECK(layer.stats.max_passes == 1);
  CHECK(count_role(layer, PathRole::Fill) == 1);
  double widest = 0;
  for (const auto& piece : layer.paths[0].pieces) widest = std::max(widest, piece.width);
  // Each piece is as wide as its strip on average; the widest point takes what one pass cannot.
  const double needed = map.thickness(3.75, layer.sample_z) - 0.9 - 1.0;
  CHECK(widest > 0.45 + needed / 2);
  CHECK(widest <= 0.45 + needed + 1e-9);
  double exact = 0;  // trapezoids of 0.001 mm
  for (double s = 0; s < 22.5; s += 0.001) exact += (map.thickness(s, layer.sample_z) + map.thickness(s + 0.001, layer.sample_z)) / 2 * 0.001;
  CHECK(layer.stats.band_area == Approx(exact).epsilon(1e-4));
  // The paper's base wall runs at the walls' slow rate: it keeps its width.
  LithoOptions paper;
  paper.base_wall = true;
  LithoLayer b;
  LithophanePlanner(map, paper).plan_layer(10, b);
  CHECK(b.stats.max_passes == 2);
}

TEST_CASE("litho planner: impossible lithophane options fail with the option named", "[litho][lithophane]") {
  const HeightMap map(flat_grey(0), plate(20));
  LithoOptions o;
  o.min_speed = 200;
  CHECK_THROWS_WITH(LithophanePlanner(map, o), Catch::Contains("--min-speed (200 mm/s) must be less than --max-speed"));
  o = {};
  o.layer_height = 0;
  CHECK_THROWS_WITH(LithophanePlanner(map, o), Catch::Contains("--layer-height"));
  o = {};
  o.layer_height = 0.5;
  CHECK_THROWS_WITH(LithophanePlanner(map, o), Catch::Contains("must be less than the nozzle"));
  o = {};
  o.min_pass_width = 2;
  CHECK_THROWS_WITH(LithophanePlanner(map, o), Catch::Contains("--min-pass-width"));
  HeightMapOptions thin = plate(20);
  thin.min_thickness = 0.3;
  const HeightMap thin_map(flat_grey(0), thin);
  CHECK_THROWS_WITH(LithophanePlanner(thin_map, LithoOptions{}), Catch::Contains("--min (0.3 mm) must be at least the nozzle"));
  const HeightMap narrow(flat_grey(0), plate(1));
  CHECK_THROWS_WITH(LithophanePlanner(narrow, LithoOptions{}), Catch::Contains("no room between its walls"));
  const LithophanePlanner ok(map, LithoOptions{});
  LithoLayer layer;
  CHECK_THROWS_AS(ok.plan_layer(ok.layer_count(), layer), std::out_of_range);
}

TEST_CASE("litho planner: a one-pixel line between two samples is followed to its full thickness", "[litho][lithophane]") {
  // 200 pixels over 20 mm (0.1 mm each), white but for one black column:
  // its centre falls between two of the 0.2 mm samples, so only the
  // picture's own corners (its knots) can put the outer wall on top of it.
  std::vector<std::uint8_t> px(200 * 10, 255);
  for (int y = 0; y < 10; ++y) px[static_cast<std::size_t>(y * 200 + 101)] = 0;
  const HeightMap map(GreyImage(200, 10, std::move(px)), plate(20));
  const LithophanePlanner planner(map, LithoOptions{});
  LithoLayer layer;
  planner.plan_layer(planner.layer_count() / 2, layer);
  const double base_y = planner.point_at(0, 0).y;
  const double lw = planner.options().line_width;
  double deepest = 0;
  std::size_t fill_pieces = 0;
  for (const auto& path : layer.paths) {
    if (path.role == PathRole::Fill) fill_pieces += path.pieces.size();
    if (path.role != PathRole::WallOuter) continue;
    for (const auto& piece : path.pieces) deepest = std::max(deepest, piece.to.y - base_y);
  }
  CHECK(deepest == Approx(3.0 - lw / 2).margin(1e-9));
  // The pass lives only on the line's two slopes (2.2 mm up and down within
  // 0.1 mm each), cut there into pieces: at least 2.2 / (4 x edge gap) of
  // them per slope, and none elsewhere. Up the slope the count goes from one
  // pass to three at once (one change of count, not two), so three passes
  // share more of it than the fewest would: at most 6 per two slopes.
  const double slope_pieces = 2.2 / (4 * planner.options().edge_gap);
  CHECK(fill_pieces >= static_cast<std::size_t>(slope_pieces));
  CHECK(fill_pieces <= static_cast<std::size_t>(6 * slope_pieces));
}

TEST_CASE("litho planner: the faster defaults lay the paper's picture surface and volume", "[litho][lithophane]") {
  // Tones come from the outer wall on the picture: at q = --max-flow with the
  // base as a bead it is the paper's (inner wall, q of infill at 100 mm/s),
  // and so is the volume; the base bead at q may widen to save passes
  // (widen_base), the paper's slow base wall does not.
  const HeightMap map(littest::gradient(64, 32), plate(40));
  LithoOptions paper;
  paper.base_wall = true;
  paper.infill_speed = 100;
  const LithophanePlanner fast(map, LithoOptions{}), slow(map, paper);
  LithoLayer a, b;
  auto outer = [](const LithoLayer& l) -> const gcode::litho::Path& {
    return *std::find_if(l.paths.begin(), l.paths.end(), [](const auto& p) { return p.role == PathRole::WallOuter; });
  };
  for (int i : {1, 37, 80}) {
    fast.plan_layer(i, a);
    slow.plan_layer(i, b);
    CHECK(a.stats.volume == Approx(b.stats.volume).epsilon(1e-12));
    CHECK(a.stats.band_area == Approx(b.stats.band_area).epsilon(1e-12));
    const auto& oa = outer(a);
    const auto& ob = outer(b);
    REQUIRE(oa.pieces.size() == ob.pieces.size());
    for (std::size_t k = 0; k < oa.pieces.size(); ++k) {
      REQUIRE(oa.pieces[k].width == Approx(ob.pieces[k].width).epsilon(1e-9));
      REQUIRE(oa.pieces[k].to.x == Approx(ob.pieces[k].to.x).epsilon(1e-12));
      REQUIRE(oa.pieces[k].to.y == Approx(ob.pieces[k].to.y).epsilon(1e-12));
      REQUIRE(oa.pieces[k].speed == Approx(ob.pieces[k].speed).epsilon(1e-9));
    }
  }
}

TEST_CASE("litho planner: over stripes only the top pass follows the picture and the pass below runs straight", "[litho][lithophane]") {
  // Stripes 4 pixels (0.5 mm) wide, 2.2 and 2.8 mm thick: gaps of 1.3 and
  // 1.9 mm, two passes in both (1.9 / 2 <= max pass width 1.0). The pass
  // along the base keeps one width the whole way (0.9 .. 1.0 mm fits both),
  // so it is one straight bead; the top pass takes what changes.
  std::vector<std::uint8_t> px(160 * 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 160; ++x)
      px[static_cast<std::size_t>(y * 160 + x)] = static_cast<std::uint8_t>(luma_for((x / 4) % 2 == 0 ? 2.2 : 2.8));
  const HeightMap map(GreyImage(160, 8, std::move(px)), plate(20));
  const LithophanePlanner planner(map, LithoOptions{});
  LithoLayer layer;
  planner.plan_layer(planner.layer_count() / 2, layer);
  CHECK(layer.stats.max_passes == 2);
  REQUIRE(count_role(layer, PathRole::Fill) == 2);  // one run per pass: the count never changes
  std::vector<const gcode::litho::Path*> passes;
  for (const auto& path : layer.paths)
    if (path.role == PathRole::Fill) passes.push_back(&path);
  // The plate's base is at its lowest Y: the pass nearer to it is the lower.
  const bool first_low = passes[0]->start.y < passes[1]->start.y;
  const gcode::litho::Path* low = passes[first_low ? 0 : 1];
  const gcode::litho::Path* top = passes[first_low ? 1 : 0];
  CHECK(low->pieces.size() == 1);  // straight at one width: one move
  for (const auto& piece : low->pieces) {
    CHECK(piece.to.y == Approx(low->start.y).margin(1e-9));
    CHECK(piece.width >= 0.9 - 1e-9);
    CHECK(piece.width <= 1.0 + 1e-9);
  }
  double narrowest = 1e9, widest = 0;
  for (const auto& piece : top->pieces) {
    narrowest = std::min(narrowest, piece.width);
    widest = std::max(widest, piece.width);
  }
  CHECK(widest - narrowest > 0.5);  // 1.9 - 1.3 mm of the picture, all in the top pass
}
