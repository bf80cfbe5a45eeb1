// The printing order of a lithophane layer (litho/path_order.hpp): the same
// beads per role as the planner made, walls first, each layer starting
// within the band's thickness of where the last one ended, every travel
// inside the band (so the G-code retracts only before the first layer and at
// the end), and a gradient cylinder's passes travelling a fraction of what
// the planner's own order would.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "gcode/core/line.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/litho/litho_gcode.hpp"
#include "gcode/litho/path_order.hpp"
#include "litho_support.hpp"

using gcode::litho::HeightMap;
using gcode::litho::HeightMapOptions;
using gcode::litho::LithoLayer;
using gcode::litho::LithoOptions;
using gcode::litho::LithophanePlanner;
using gcode::litho::LithoShape;
using gcode::litho::Path;
using gcode::litho::PathRole;
using gcode::litho::Point;

namespace {

HeightMapOptions shape(bool closed) {
  HeightMapOptions o;
  o.width = 40;
  if (closed) {
    o.shape = LithoShape::Cylinder;
    o.diameter = 16;
    o.height = 12;
  }
  return o;
}

// One slot for each PathRole (WallOuter, WallInner, Base, Fill).
constexpr int kPathOrderRoles = static_cast<int>(gcode::litho::PathRole::Fill) + 1;

struct Totals {
  double volume[kPathOrderRoles] = {};
  double length[kPathOrderRoles] = {};
  std::size_t clamped = 0;
};

Totals totals(const LithoLayer& layer) {
  Totals t;
  for (const Path& p : layer.paths) {
    Point at = p.start;
    const auto r = static_cast<std::size_t>(p.role);
    for (const auto& piece : p.pieces) {
      t.volume[r] += piece.volume;
      t.length[r] += distance(at, piece.to);
      t.clamped += piece.clamped;
      at = piece.to;
    }
  }
  return t;
}

}  // namespace

TEST_CASE("litho path order: same beads, walls first, each layer starts where the last ended, travel inside the band",
          "[litho][path_order]") {
  for (bool closed : {false, true}) {
    INFO((closed ? "cylinder" : "flat"));
    const HeightMap map(littest::strokes(120, 60), shape(closed));
    const LithophanePlanner planner(map, LithoOptions{});
    LithoLayer plain, ordered;
    Point head;
    double worst_start = 0;
    std::size_t combed = 0;
    for (int i = 0; i < planner.layer_count(); ++i) {
      const Point before = head;
      gcode::litho::plan_ordered_layer(planner, i, ordered, head);
      planner.plan_layer(i, plain);
      // The same plastic in the same places: per role, the volume and the
      // length of the beads (a piece cut in two where a loop starts adds no length).
      const Totals a = totals(plain), b = totals(ordered);
      for (int r = 0; r < kPathOrderRoles; ++r) {
        REQUIRE(b.volume[r] == Approx(a.volume[r]).epsilon(1e-12));
        REQUIRE(b.length[r] == Approx(a.length[r]).epsilon(1e-9));
      }
      // Walls, then passes.
      const auto first_fill = std::find_if(ordered.paths.begin(), ordered.paths.end(),
                                           [](const Path& p) { return p.role == PathRole::Fill; });
      REQUIRE(std::all_of(first_fill, ordered.paths.end(), [](const Path& p) { return p.role == PathRole::Fill; }));
      if (i > 0) worst_start = std::max(worst_start, distance(before, ordered.paths.front().start));
      REQUIRE(head.x == end_of(ordered.paths.back()).x);
      // Every travel, through its waypoints, stays in the band (every 0.02 mm);
      // the first one of a layer may begin over the band of the layer below.
      Point at = i == 0 ? ordered.paths.front().start : before;
      const double below_z = std::max(0.0, ordered.sample_z - planner.options().layer_height);
      for (const Path& p : ordered.paths) {
        const bool first = &p == &ordered.paths.front();
        REQUIRE(p.combed);
        REQUIRE(distance(p.from, at) < 1e-12);
        std::vector<Point> way{p.from};
        way.insert(way.end(), p.approach.begin(), p.approach.end());
        way.push_back(p.start);
        combed += !p.approach.empty();
        for (std::size_t k = 0; k + 1 < way.size(); ++k) {
          const int n = std::max(1, static_cast<int>(distance(way[k], way[k + 1]) / 0.02));
          for (int j = 0; j <= n; ++j) {
            const double f = static_cast<double>(j) / n;
            double s = 0, d = 0;
            map.locate({way[k].x + (way[k + 1].x - way[k].x) * f, way[k].y + (way[k + 1].y - way[k].y) * f},
                       planner.options().center_x, planner.options().center_y, s, d);
            INFO("layer " << i << " s " << s << " depth " << d);
            REQUIRE(d >= -1e-6);
            const double t = map.thickness(s, ordered.sample_z);
            REQUIRE(d <= (first ? std::max(t, map.thickness(s, below_z)) : t) + 1e-6);
          }
        }
        at = end_of(p);
      }
    }
    // A layer begins within the band's thickness of where the one below ended
    // (the planner's own order starts every layer at the same place).
    CHECK(worst_start <= map.max_thickness());
    // Some travels had to go round the picture's relief.
    CHECK(combed > 0);
  }
}

TEST_CASE("litho path order: the G-code retracts only before the first layer's travel and at the end",
          "[litho][path_order]") {
  const HeightMap map(littest::strokes(120, 60), shape(false));
  const LithophanePlanner planner(map, LithoOptions{});
  std::string text;
  gcode::litho::write_litho_gcode(planner, {}, [&](std::string_view chunk) { text.append(chunk); });
  gcode::MachineState state;
  gcode::MemoryLineSplitter split(text);
  gcode::RawLine raw;
  int layer = -1;
  std::size_t inside = 0, travels = 0;
  while (split.next(raw)) {
    if (raw.text.starts_with(";LAYER:")) layer = std::stoi(std::string(raw.text.substr(7)));
    const gcode::Move m = state.apply(gcode::Line::parse(raw.text));
    if (layer >= 1 && m.retraction()) ++inside;
    if (layer >= 1 && m.travel && m.moves_head()) ++travels;
  }
  CHECK(travels > 1000);
  CHECK(inside == 1);  // the end code's
}

TEST_CASE("litho path order: passes of a gradient cylinder need a fraction of the planner order's travel",
          "[litho][path_order]") {
  // Round the cylinder the thickness climbs from 0.8 to 3.0 mm: groups of
  // none, one, two and three passes. Printed in the planner's order from
  // where the walls end, the runs of a group that ends on the wrong side
  // need a travel back; the Euler path pairs up only the odd positions.
  HeightMapOptions o;
  o.shape = LithoShape::Cylinder;
  o.diameter = 30;
  o.height = 10;
  const HeightMap map(littest::gradient(64, 16), o);
  const LithophanePlanner planner(map, LithoOptions{});
  LithoLayer plain, ordered;
  Point head;
  double plain_travel = 0, ordered_travel = 0;
  for (int i = 0; i < planner.layer_count(); ++i) {
    const Point before = head;
    gcode::litho::plan_ordered_layer(planner, i, ordered, head);
    planner.plan_layer(i, plain);
    // The planner's order, from the same start, straight (which only flatters it).
    Point at = i == 0 ? plain.paths.front().start : before;
    for (const Path& p : plain.paths) {
      plain_travel += distance(at, p.start);
      at = end_of(p);
    }
    at = i == 0 ? ordered.paths.front().start : before;
    for (const Path& p : ordered.paths) {
      for (const Point& via : p.approach) {
        ordered_travel += distance(at, via);
        at = via;
      }
      ordered_travel += distance(at, p.start);
      at = end_of(p);
    }
  }
  std::printf("litho path order: gradient cylinder travel %.0f mm in the planner's order, %.0f mm ordered\n",
              plain_travel, ordered_travel);
  CHECK(ordered_travel < 0.25 * plain_travel);
}
