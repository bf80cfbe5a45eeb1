#include "gcode/procedural/shape_gcode.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "gcode/core/line_builder.hpp"
#include "gcode/core/number.hpp"
#include "gcode/core/start_end_code.hpp"
#include "gcode/version.hpp"

namespace gcode::procedural {

namespace {

constexpr int kXYZ = 3;
constexpr double kUnit = 1e-3;  // of X, Y and Z as written
constexpr int kE = 5;
constexpr double kLift = 2;     // mm above the path for the travel to its start

double filament_area(const ShapeGcodeOptions& o) {
  return std::numbers::pi * o.filament_diameter * o.filament_diameter / 4;
}

// Writes the path's moves: the head position as written, the modal F and the
// E rounding carry (each piece gets the exact running total, rounded, less
// what was written before).
class PathWriter {
 public:
  PathWriter(const ShapeGcodeOptions& options, double line_width)
      : options_(options), width_(line_width), area_(filament_area(options)) {}

  std::string& text() { return text_; }
  void line(std::string_view s) {
    text_.append(s);
    text_.push_back('\n');
  }
  void set_position(const PathPoint& p) {
    at_ = p;
    for (int a = 0; a < 3; ++a) written_[a] = to_scaled(a == 0 ? p.x : (a == 1 ? p.y : p.z), kXYZ);
  }

  // A layer that starts its own bead (ShapeLayer::start_bead).
  void restart_bead(double bead) {
    if (bead >= 0) at_.bead = bead_written_ = bead;
  }

  // A bead from the current point to `to`; one that rounds to no move at all
  // hands its plastic to the next.
  void extrude_to(const PathPoint& to) {
    const std::int64_t target[3] = {to_scaled(to.x, kXYZ), to_scaled(to.y, kXYZ), to_scaled(to.z, kXYZ)};
    double d2 = 0;
    for (int a = 0; a < 3; ++a) d2 += std::pow(static_cast<double>(target[a] - written_[a]), 2);
    const double length = std::sqrt(d2) * kUnit;
    if (length == 0) {
      pending_ += width_ * (at_.bead + to.bead) / 2 * std::hypot(to.x - at_.x, to.y - at_.y, to.z - at_.z);
      at_ = to;
      return;
    }
    at_ = to;
    b_.start("G1");
    feed(options_.speed);
    b_.word('X', to.x, kXYZ).word('Y', to.y, kXYZ);
    if (target[2] != written_[2]) b_.word('Z', to.z, kXYZ);
    // The bead's volume over the length as written: the cross-section exact on every piece.
    e_exact_ += (pending_ + width_ * (bead_written_ + to.bead) / 2 * length) / area_;
    pending_ = 0;
    bead_written_ = to.bead;
    const std::int64_t total = to_scaled(e_exact_, kE);
    char buf[kMaxNumberChars];
    b_.text(" E").text(std::string_view(buf, format_scaled(total - e_total_, kE, buf)));
    e_total_ = total;
    for (int a = 0; a < 3; ++a) written_[a] = target[a];
    line(b_.view());
    ++moves_;
    length_ += length;
  }

  // Pulls the filament back (or, `undo`, pushes it again).
  void retract(bool undo = false) {
    if (options_.retract_length <= 0) return;
    b_.start("G1");
    feed(options_.retract_speed);
    b_.word('E', undo ? options_.retract_length : -options_.retract_length, kE);
    line(b_.view());
  }

  // A short travel inside a flat fill: straight there, no lift, no retraction.
  void hop(const PathPoint& to) {
    b_.start("G0");
    feed(options_.travel_speed);
    b_.word('X', to.x, kXYZ).word('Y', to.y, kXYZ);
    if (to_scaled(to.z, kXYZ) != written_[2]) b_.word('Z', to.z, kXYZ);
    line(b_.view());
    pending_ = 0;
    set_position(to);
    bead_written_ = to.bead;
  }

  void go(const PathPoint& to) {
    if (to.travel) hop(to);
    else extrude_to(to);
  }

  void travel(const PathPoint& to, double lift_z) {
    auto go = [&](std::string_view words) {
      b_.start("G0");
      feed(options_.travel_speed);
      line(b_.text(words).view());
    };
    go(" Z" + number_string(lift_z, 3));
    go(" X" + number_string(to.x, 3) + " Y" + number_string(to.y, 3));
    go(" Z" + number_string(to.z, 3));
    set_position(to);
    bead_written_ = to.bead;
  }

  double filament() const { return static_cast<double>(e_total_) / 1e5; }
  double length() const { return length_; }
  std::size_t moves() const { return moves_; }
  double z() const { return at_.z; }

 private:
  void feed(double mm_per_s) {
    const std::int64_t f = to_scaled(mm_per_s * 60, 0);
    if (f == feed_) return;
    feed_ = f;
    b_.text(" F" + number_string(static_cast<double>(f), 0));
  }

  const ShapeGcodeOptions& options_;
  double width_;
  double area_;
  std::string text_;
  LineBuilder b_;
  PathPoint at_;
  std::int64_t written_[3] = {};
  std::int64_t feed_ = -1;
  double pending_ = 0;
  double bead_written_ = 0;
  double e_exact_ = 0;
  std::int64_t e_total_ = 0;
  double length_ = 0;
  std::size_t moves_ = 0;
};

// Totals for the header: the same pieces the writer writes.
ShapeGcodeStats dry_run(const ShapePath& path, const ShapeGcodeOptions& options) {
  PathWriter w(options, path.options().line_width);
  w.set_position(path.start());
  ShapeLayer layer;
  for (int i = 0; i < path.layer_count(); ++i) {
    path.layer(i, layer);
    w.restart_bead(layer.start_bead);
    for (const PathPoint& p : layer.points) w.go(p);
    w.text().clear();
  }
  return {path.layer_count(), w.filament(), w.length(), w.moves()};
}

void write_header(const ShapePath& path, const ShapeGcodeOptions& options, const ShapeGcodeStats& totals,
                  PathWriter& w) {
  const ShapeOptions& o = path.options();
  const Box2 box = path.box();
  w.line(";FLAVOR:Marlin");
  w.line(fmt::format(";Filament used: {}m", number_string(totals.filament / 1000, 5)));
  w.line(fmt::format(";Layer height: {}", number_string(o.layer_height, 3)));
  w.line(fmt::format(";MINX:{}", number_string(box.min_x, 3)));
  w.line(fmt::format(";MINY:{}", number_string(box.min_y, 3)));
  w.line(fmt::format(";MINZ:{}", number_string(path.start().z, 3)));
  w.line(fmt::format(";MAXX:{}", number_string(box.max_x, 3)));
  w.line(fmt::format(";MAXY:{}", number_string(box.max_y, 3)));
  w.line(fmt::format(";MAXZ:{}", number_string(path.top(), 3)));
  w.line("");
  w.line(fmt::format(";Generated with gc-shape {}: a {} printed as one seamless path, without a slicer", kVersion,
                     shape_kind_name(o.kind)));
  for (const std::string& p : shape_parameters(path, options)) w.line(";  " + p);
  w.line(fmt::format(";  moves = {}, extruded path = {} mm", totals.moves, number_string(totals.length, 1)));
}

void write_start(const ShapePath& path, const ShapeGcodeOptions& options, PathWriter& w) {
  const ShapeOptions& o = path.options();
  const PathPoint start = path.start();
  const Box2 box = path.box();
  double lift = start.z + kLift;
  if (options.start_code.empty()) {
    MarlinStart s{.nozzle_temp = options.nozzle_temp, .bed_temp = options.bed_temp,
                  .travel_speed = options.travel_speed, .purge_x0 = box.min_x,
                  .purge_x1 = std::max(box.max_x, box.min_x + 20), .purge_y = box.min_y - 5,
                  .purge_z = o.layer_height, .e_decimals = kE};
    s.purge_filament = o.line_width * o.layer_height * (s.purge_x1 - s.purge_x0) * 1.2 / filament_area(options);
    w.text() += marlin_start_code(s);
    lift = std::max(lift, s.purge_z + kLift);
    w.retract();
  } else {
    w.text() += with_final_newline(options.start_code);
    w.line("G90");
    w.line("M83 ; relative extrusion: each E below is one piece's filament");
  }
  w.travel(start, lift);
  if (options.start_code.empty()) w.retract(/*undo=*/true);
  w.line(fmt::format(";LAYER_COUNT:{}", path.layer_count()));
}

}  // namespace

void ShapeGcodeOptions::validate() const {
  auto check = [](bool ok, const char* message) {
    if (!ok) throw std::invalid_argument(message);
  };
  auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  check(positive(speed), "--speed must be above 0");
  check(positive(travel_speed), "--travel-speed must be above 0");
  check(positive(filament_diameter), "--filament-diameter must be above 0");
  check(std::isfinite(nozzle_temp) && nozzle_temp >= 0 && nozzle_temp <= 450, "--nozzle-temp must be 0..450 C");
  check(std::isfinite(bed_temp) && bed_temp >= 0 && bed_temp <= 150, "--bed-temp must be 0..150 C");
  check(std::isfinite(retract_length) && retract_length >= 0, "--retract must be 0 or above");
  check(positive(retract_speed), "--retract-speed must be above 0");
  check(fan >= 0 && fan <= 255, "--fan must be 0..255");
}

std::vector<std::string> shape_parameters(const ShapePath& path, const ShapeGcodeOptions& options) {
  const ShapeOptions& o = path.options();
  std::vector<std::string> p;
  auto add = [&](std::string_view name, const std::string& value) { p.push_back(fmt::format("{} = {}", name, value)); };
  add("shape", std::string(shape_kind_name(o.kind)));
  for (const std::string& line : path.laid().parameters) p.push_back(line);
  if (o.kind != ShapeKind::Vase) add("diameter", number_string(o.diameter, 3) + " mm (the path's centre line)");
  if (o.kind == ShapeKind::Cone) add("top_diameter", number_string(o.top_diameter, 3) + " mm");
  if (o.kind == ShapeKind::Spiral)
    add("inner_diameter", number_string(2 * path.start().x - 2 * o.center_x, 3) + " mm outer, " +
                              number_string(o.inner_diameter > 0 ? o.inner_diameter : 4 * o.line_width, 3) +
                              " mm inner");
  if (o.kind == ShapeKind::Polygon) add("sides", std::to_string(o.sides));
  add("height", number_string(path.top(), 3) + " mm");
  add("layer_height", number_string(o.layer_height, 3) + " mm");
  if (path.turns() > 0) add("pitch", fmt::format("{} mm, {} turns", number_string(path.pitch(), 6), path.turns()));
  add("layers", std::to_string(path.layer_count()));
  add("line_width", number_string(o.line_width, 3) + " mm");
  add("cross_section", number_string(o.line_width * o.layer_height, 5) + " mm2");
  add("tolerance", number_string(o.tolerance, 4) + " mm");
  add("center", number_string(o.center_x, 3) + "," + number_string(o.center_y, 3) + " mm");
  add("speed", number_string(options.speed, 3) + " mm/s");
  add("travel_speed", number_string(options.travel_speed, 3) + " mm/s");
  add("filament_diameter", number_string(options.filament_diameter, 3) + " mm");
  add("nozzle_temp", number_string(options.nozzle_temp, 3) + " C");
  add("bed_temp", number_string(options.bed_temp, 3) + " C");
  add("retract",
      number_string(options.retract_length, 5) + " mm at " + number_string(options.retract_speed, 3) + " mm/s");
  add("fan", std::to_string(options.fan));
  add("start", options.start_code.empty() ? "built-in Marlin" : (options.start_name.empty() ? "given" : options.start_name));
  add("end", options.end_code.empty() ? "built-in Marlin" : (options.end_name.empty() ? "given" : options.end_name));
  return p;
}

ShapeGcodeStats write_shape_gcode(const ShapePath& path, const ShapeGcodeOptions& options, const ShapeTextOut& out) {
  options.validate();
  const ShapeGcodeStats totals = dry_run(path, options);
  PathWriter w(options, path.options().line_width);
  auto emit = [&] {
    out(w.text());
    w.text().clear();
  };
  write_header(path, options, totals, w);
  write_start(path, options, w);
  emit();
  ShapeLayer layer;
  bool bottom = false;
  for (int i = 0; i < path.layer_count(); ++i) {
    path.layer(i, layer);
    w.line(fmt::format(";LAYER:{}", i));
    if (i == 1 && options.fan > 0) w.line(fmt::format("M106 S{}", options.fan));
    if (i == 0 || layer.bottom != bottom) w.line(layer.bottom ? ";TYPE:SKIN" : ";TYPE:WALL-OUTER");
    bottom = layer.bottom;
    w.restart_bead(layer.start_bead);
    for (const PathPoint& p : layer.points) w.go(p);
    emit();
  }
  if (options.end_code.empty()) {
    w.retract();
    w.text() += marlin_end_code(w.z() + 10);
  } else {
    w.text() += with_final_newline(options.end_code);
  }
  emit();
  return {path.layer_count(), w.filament(), w.length(), w.moves()};
}

}  // namespace gcode::procedural
