// What a pausing stream keeps (transform/pause_context.hpp): the file's own
// pending retraction, the highest Z printed, the XY extent printed inside
// layers; and where to park: --park as given (rounded to the file's
// decimals), else the back of the bed centred on the print, refused above
// the print when filament is pushed there.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>

#include "gcode/pipeline/pipeline.hpp"
#include "gcode/transform/pause_context.hpp"
#include "fn_stage.hpp"

using gcode::Box2;
using gcode::ParkRules;
using gcode::PauseConfig;
using gcode::PauseContext;

namespace {

// `text` through a pipeline whose stage observes every line.
PauseContext observed(const std::string& text, gcode::Precision* precision = nullptr) {
  PauseContext context;
  gcode::LayerMarkers markers;
  gcode::Pipeline pipeline(markers);
  gctest::FnStage stage([&](const gcode::TrackedLine& t, gcode::Emitter& out) {
    context.observe(t);
    out.pass(t);
  });
  pipeline.add(stage);
  pipeline.run_text(text);
  if (precision != nullptr) *precision = pipeline.precision();
  return context;
}

const char* kPrint =
    "M83\nG28\nG1 Z0.3 F600\n"
    "G1 X0 Y-3 E0\nG1 X100 Y-3 E12\n"  // a purge line in the start code
    ";LAYER:0\nG1 Z0.2\nG1 X40 Y50 E0\nG1 X60 Y50 E1\nG1 X60 Y70 E1\n"
    "G1 E-0.8 F2100\nG1 Z5\nG1 X55 Y60\nG1 Z0.4\nG1 E0.8\n"  // retract, hop, travel, unretract
    ";LAYER:1\nG1 X45 Y65 E1\nG1 X50 Y55 E-0.5\n";           // a wipe: moving while retracting

ParkRules bed_220() {
  ParkRules rules;
  rules.area.has_bed = true;
  rules.area.bed = Box2{0, 0, 220, 220};
  return rules;
}

std::string place_error(const ParkRules& rules, const PauseContext& context, PauseConfig config) {
  try {
    rules.place(context, gcode::Precision(), config);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("pause context: top Z and extent come from extrusions inside layers", "[pause_context]") {
  PauseContext c = observed(kPrint);
  CHECK(c.top_z() == 0.4);  // the hop to Z5 printed nothing
  Box2 box = c.printed();
  CHECK(box.min_x == 40);   // the purge line (X0..100, Y-3) is start code
  CHECK(box.max_x == 60);
  CHECK(box.min_y == 50);
  CHECK(box.max_y == 70);
  CHECK(PauseContext().printed().empty());
  CHECK(PauseContext().top_z() == 0);
}

TEST_CASE("pause context: the file's own retraction is pending until extrusion", "[pause_context]") {
  std::string upto_hop = kPrint;
  upto_hop = upto_hop.substr(0, upto_hop.find("G1 Z0.4\n"));
  CHECK(observed(upto_hop).pending_retraction() == Approx(0.8).margin(1e-12));
  std::string unretracted = kPrint;
  unretracted = unretracted.substr(0, unretracted.find(";LAYER:1"));
  CHECK(observed(unretracted).pending_retraction() == 0);
  CHECK(observed(kPrint).pending_retraction() == Approx(0.5).margin(1e-12));  // the wipe
  // More pushed back than retracted is no negative retraction.
  CHECK(observed("M83\nG1 X1 E1\nG1 E-1\nG1 E3\n").pending_retraction() == 0);
}

TEST_CASE("pause context: the pause point carries state, retraction, top Z and precision", "[pause_context]") {
  PauseContext c = observed(kPrint);
  gcode::MachineState s;
  gcode::Precision p;
  gcode::PausePoint point = c.point(s, &p);
  CHECK(&point.state == &s);
  CHECK(point.pending_retraction == c.pending_retraction());
  CHECK(point.top_z == 0.4);
  CHECK(point.precision == &p);
}

TEST_CASE("park rules: no --park and no bed size is an error", "[pause_context]") {
  ParkRules none;
  CHECK_THROWS_WITH(none.check(), Catch::Contains("give --park X,Y (or --bed WIDTHxDEPTH)"));
  ParkRules given;
  given.given = true;
  CHECK_NOTHROW(given.check());
  CHECK_NOTHROW(bed_220().check());
  CHECK(place_error(none, PauseContext(), PauseConfig()).find("park position is unknown") != std::string::npos);
}

TEST_CASE("park rules: a live pause without a park position lifts where it is and pushes nothing there",
          "[pause_context]") {
  PauseContext c = observed(kPrint);
  PauseConfig config;
  config.reload = 10;
  config.purge = 5;
  config.prime = 1;
  std::string note = ParkRules().place_or_lift(c, gcode::Precision(), config);
  CHECK(note.find("no park position") != std::string::npos);
  CHECK(note.find("no reload, purge or prime") != std::string::npos);
  CHECK_FALSE(config.park);
  CHECK(config.reload == 0);
  CHECK(config.purge == 0);
  CHECK(config.prime == 0);
  // With a bed it parks as place() does, and says nothing.
  PauseConfig parked;
  CHECK(bed_220().place_or_lift(c, gcode::Precision(), parked).empty());
  CHECK(parked.park);
  CHECK(parked.park_y == 210);
}

TEST_CASE("park rules: the back of the bed, centred on the print", "[pause_context]") {
  PauseContext c = observed(kPrint);
  PauseConfig config;
  bed_220().place(c, gcode::Precision(), config);
  CHECK(config.park_x == 50);   // centre of X 40..60
  CHECK(config.park_y == 210);  // bed depth - 10
  // With the slicer's box too: both count.
  ParkRules rules = bed_220();
  rules.area.has_print_box = true;
  rules.area.print_box = Box2{100, 100, 140, 120};
  CHECK(rules.print_box(c).min_x == 40);
  CHECK(rules.print_box(c).max_x == 140);
  rules.place(c, gcode::Precision(), config);
  CHECK(config.park_x == 90);
  // Nothing printed, nothing known: the bed's centre.
  bed_220().place(PauseContext(), gcode::Precision(), config);
  CHECK(config.park_x == 110);
}

TEST_CASE("park rules: a park position has no more decimals than the file", "[pause_context]") {
  ParkRules rules;
  rules.given = true;
  rules.x = 100.123456;
  rules.y = 0.0005;
  PauseConfig config;
  gcode::Precision p;  // X/Y 3
  rules.place(PauseContext(), p, config);
  CHECK(config.park_x == 100.123);
  CHECK(config.park_y == 0.001);
  p.observe('X', 5);
  rules.place(PauseContext(), p, config);
  CHECK(config.park_x == 100.12346);
  // The centre of an odd-width print, 10..20.555: 15.2775 -> 15.278.
  ParkRules bed = bed_220();
  bed.area.has_print_box = true;
  bed.area.print_box = Box2{10, 10, 20.555, 20};
  bed.place(PauseContext(), gcode::Precision(), config);
  CHECK(config.park_x == 15.278);
}

TEST_CASE("park rules: no purge above the print", "[pause_context]") {
  PauseContext c = observed(kPrint);
  ParkRules over;
  over.given = true;
  over.x = 50;
  over.y = 60;
  PauseConfig quiet;  // nothing pushed: parking above is allowed
  CHECK(place_error(over, c, quiet) == "no error");
  for (double PauseConfig::*push : {&PauseConfig::reload, &PauseConfig::purge, &PauseConfig::prime}) {
    PauseConfig config;
    config.*push = 10;
    CHECK(place_error(over, c, config) ==
          "the park position X50 Y60 is above the print (X 40..60, Y 50..70): purging there would drop a blob on it; "
          "choose --park outside the print");
  }
  // On the print's edge is above it; just outside is not.
  PauseConfig purge;
  purge.purge = 10;
  over.x = 60;
  CHECK(place_error(over, c, purge) != "no error");
  over.x = 60.001;
  CHECK(place_error(over, c, purge) == "no error");
}

TEST_CASE("pause context: the printed side of a seam, settings and E mode included", "[pause][context]") {
  PauseContext c = observed(
      "M140 S60\nM104 S215\nM83\nG28\nG1 Z0.3 F600\n"
      ";LAYER:0\nG1 Z0.2\nG1 X40 Y50 E0\nG1 X60 Y50 E1\nM106 S128\n"
      ";LAYER:1\nG1 Z0.4\nG1 X60 Y70 E1\nG1 E-0.8 F2400\nM104 S210\n");
  gcode::MachineState at;
  at.set(gcode::kX, gcode::Fixed::from_double(60));
  gcode::StreamPoint p = c.stream_point(at);
  CHECK(p.state.at(gcode::kX) == at.at(gcode::kX));
  CHECK(p.retracted == Approx(0.8));
  CHECK(p.top_z == Approx(0.4));
  CHECK(p.e_mode_set);
  CHECK(p.extent.max_y == Approx(70));
  using Kind = gcode::CarriedSettings::Kind;
  REQUIRE(p.settings.find(Kind::Hotend, 0) != nullptr);
  CHECK(p.settings.find(Kind::Hotend, 0)->value == gcode::Fixed::from_double(210));  // the last one said
  REQUIRE(p.settings.find(Kind::Bed, 0) != nullptr);
  CHECK(p.settings.find(Kind::Fan, 0)->value == gcode::Fixed::from_double(128));
  CHECK_FALSE(observed("G1 X1 Y1 E1\n").stream_point(at).e_mode_set);
}
