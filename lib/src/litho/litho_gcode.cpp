#include "gcode/litho/litho_gcode.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "gcode/core/line_builder.hpp"
#include "gcode/core/number.hpp"
#include "gcode/core/start_end_code.hpp"
#include "gcode/litho/path_order.hpp"
#include "gcode/version.hpp"

namespace gcode::litho {

namespace {

constexpr int kXY = 4;   // X and Y: pieces on steep edges are a few micrometres along the base
constexpr double kXYUnit = 1e-4;
constexpr int kXYZ = 3;  // Z
constexpr int kE = 7;

const char* type_name(PathRole role) {
  switch (role) {
    case PathRole::WallOuter:
      return ";TYPE:WALL-OUTER";
    case PathRole::WallInner:
      return ";TYPE:WALL-INNER";
    case PathRole::Base:
    case PathRole::Fill:
      break;
  }
  return ";TYPE:FILL";
}

// Turns paths into lines. Keeps the head position, the modal F, and the E
// rounding carry (relative E: each piece gets the exact running total,
// rounded, minus what was already written).
class Emitter {
 public:
  Emitter(const LithoGcodeOptions& options, double filament_area, double layer_height)
      : options_(options), filament_area_(filament_area), layer_height_(layer_height) {}

  std::string& text() { return text_; }

  void line(std::string_view s) {
    text_.append(s);
    text_.push_back('\n');
  }

  void feed(LineBuilder& b, double mm_per_s) {
    const std::int64_t f = to_scaled(mm_per_s * 60, 0);
    if (f != feed_) {
      feed_ = f;
      char buf[kMaxNumberChars];
      b.text(" F");
      b.text(std::string_view(buf, format_scaled(f, 0, buf)));
    }
  }

  // E is the planned width over the length as written (coordinates rounded
  // to 3 decimals), so the bead's width, and with it the extruder rate at
  // the written F, are what the planner asked for. A piece that rounds to no
  // length at all is not written; its plastic goes to the next piece.
  void extrude_to(const Piece& piece) {
    const std::int64_t x = to_scaled(piece.to.x, kXY);
    const std::int64_t y = to_scaled(piece.to.y, kXY);
    if (x == x_ && y == y_) {
      pending_volume_ += piece.volume;
      return;
    }
    const double length = std::hypot(static_cast<double>(x - x_), static_cast<double>(y - y_)) * kXYUnit;
    b_.start("G1");
    feed(b_, piece.speed);
    b_.word('X', piece.to.x, kXY).word('Y', piece.to.y, kXY);
    e_exact_ += (piece.width * layer_height_ * length + pending_volume_) / filament_area_;
    pending_volume_ = 0;
    const std::int64_t total = to_scaled(e_exact_, kE);
    char buf[kMaxNumberChars];
    b_.text(" E");
    b_.text(std::string_view(buf, format_scaled(total - e_written_, kE, buf)));
    e_written_ = total;
    line(b_.view());
    set_at(piece.to);
  }

  void retract(bool out) {
    if (options_.retract_length <= 0 || retracted_ == out) return;
    b_.start("G1");
    feed(b_, options_.retract_speed);
    b_.word('E', out ? -options_.retract_length : options_.retract_length, kE);
    line(b_.view());
    retracted_ = out;
  }

  // Travel to `to` at height `z` (Z first when going up, last when going down).
  void travel(Point to, double z) {
    const double d = std::hypot(to.x - at_.x, to.y - at_.y);
    const bool moves_xy = to_scaled(to.x, kXY) != x_ || to_scaled(to.y, kXY) != y_;
    const bool moves_z = to_scaled(z, kXYZ) != to_scaled(z_, kXYZ);
    if (!moves_xy && !moves_z) return;
    if (d > options_.retract_min_travel || moves_z) retract(true);
    if (moves_z && z > z_) move_z(z);
    if (moves_xy) travel_xy(to);
    if (moves_z && z < z_) move_z(z);
  }

  // A travel the planner routed inside the band (path_order.hpp), taken only
  // from where it was routed from: over the part, so no retraction.
  bool combed_travel(const Path& p, double z) {
    if (!p.combed || to_scaled(p.from.x, kXY) != x_ || to_scaled(p.from.y, kXY) != y_) return false;
    if (to_scaled(z, kXYZ) != to_scaled(z_, kXYZ)) {
      if (z < z_) return false;
      move_z(z);
    }
    for (const Point& via : p.approach) travel_xy(via);
    travel_xy(p.start);
    return true;
  }

  void path(const Path& p, double z) {
    if (p.pieces.empty()) return;
    if (!combed_travel(p, z)) travel(p.start, z);
    retract(false);
    if (std::string_view(type_name(p.role)) != type_name(role_) || !typed_) {
      line(type_name(p.role));
      role_ = p.role;
      typed_ = true;
    }
    for (const Piece& piece : p.pieces) extrude_to(piece);
  }

  void new_layer() { typed_ = false; }
  void set_position(Point at, double z) {
    set_at(at);
    z_ = z;
  }
  double z() const { return z_; }
  double filament_written() const { return static_cast<double>(e_written_) / std::pow(10.0, kE); }

 private:
  void set_at(Point at) {
    at_ = at;
    x_ = to_scaled(at.x, kXY);
    y_ = to_scaled(at.y, kXY);
  }

  void travel_xy(Point to) {
    if (to_scaled(to.x, kXY) == x_ && to_scaled(to.y, kXY) == y_) return;
    b_.start("G0");
    feed(b_, options_.travel_speed);
    b_.word('X', to.x, kXY).word('Y', to.y, kXY);
    line(b_.view());
    set_at(to);
  }

  void move_z(double z) {
    b_.start("G0");
    feed(b_, options_.travel_speed);
    b_.word('Z', z, kXYZ);
    line(b_.view());
    z_ = z;
  }

  const LithoGcodeOptions& options_;
  double filament_area_;
  double layer_height_;
  std::string text_;
  LineBuilder b_;
  Point at_;
  std::int64_t x_ = 0, y_ = 0;  // at_ as written
  double z_ = 0;
  std::int64_t feed_ = -1;
  double e_exact_ = 0;
  double pending_volume_ = 0;
  std::int64_t e_written_ = 0;
  bool retracted_ = false;
  bool typed_ = false;
  PathRole role_ = PathRole::Fill;
};

}  // namespace

void LithoGcodeOptions::validate() const {
  auto check = [](bool ok, const char* message) {
    if (!ok) throw std::invalid_argument(message);
  };
  check(std::isfinite(nozzle_temp) && nozzle_temp >= 0 && nozzle_temp <= 450, "--nozzle-temp must be 0..450 C");
  check(std::isfinite(bed_temp) && bed_temp >= 0 && bed_temp <= 150, "--bed-temp must be 0..150 C");
  check(std::isfinite(travel_speed) && travel_speed > 0, "--travel-speed must be above 0");
  check(std::isfinite(retract_length) && retract_length >= 0, "--retract must be 0 or above");
  check(std::isfinite(retract_speed) && retract_speed > 0, "--retract-speed must be above 0");
  check(std::isfinite(retract_min_travel) && retract_min_travel >= 0, "--retract-min-travel must be 0 or above");
  check(fan >= 0 && fan <= 255, "--fan must be 0..255");
  check(std::isfinite(estimated_seconds) && estimated_seconds >= 0, "the estimated time must be 0 or above");
}

BedBounds litho_bounds(const LithophanePlanner& planner) {
  const HeightMap& map = planner.map();
  const LithoOptions& o = planner.options();
  if (map.closed()) {
    const double r = map.base_radius() + map.max_thickness();
    return {o.center_x - r, o.center_y - r, o.center_x + r, o.center_y + r};
  }
  const Point a = planner.point_at(0, 0);
  const Point b = planner.point_at(map.length(), map.max_thickness());
  return {a.x, a.y, b.x, b.y};
}

std::vector<std::string> litho_parameters(const LithophanePlanner& planner, const LithoGcodeOptions& options) {
  const HeightMap& map = planner.map();
  const HeightMapOptions& m = map.options();
  const LithoOptions& o = planner.options();
  std::vector<std::string> p;
  auto add = [&](std::string_view name, std::string value) { p.push_back(fmt::format("{} = {}", name, value)); };
  add("image", fmt::format("{} ({} x {} pixels)", options.image_name.empty() ? "-" : options.image_name,
                           map.image().width(), map.image().height()));
  add("shape", map.closed() ? "cylinder" : "flat");
  if (map.closed()) {
    add("diameter", number_string(m.diameter, 3) + " mm (base surface)");
    add("circumference", number_string(map.length(), 3) + " mm");
  } else {
    add("width", number_string(map.length(), 3) + " mm");
  }
  add("height", number_string(map.height(), 3) + " mm");
  add("min", number_string(m.min_thickness, 3) + " mm");
  add("max", number_string(m.max_thickness, 3) + " mm");
  add("border", number_string(m.border, 3) + " mm");
  add("invert", m.tone.invert ? "yes" : "no");
  add("gamma", number_string(m.tone.gamma, 3));
  add("contrast", number_string(m.tone.contrast, 3));
  add("layer_height", number_string(o.layer_height, 3) + " mm");
  add("layers", std::to_string(planner.layer_count()));
  add("nozzle", number_string(o.nozzle, 3) + " mm");
  add("line_width", number_string(o.line_width, 3) + " mm");
  add("filament_diameter", number_string(o.filament_diameter, 3) + " mm");
  add("wall_speed", number_string(o.wall_speed, 3) + " mm/s");
  add("infill_speed", number_string(o.infill_speed, 3) + " mm/s");
  add("max_flow", number_string(o.max_flow, 3) + " mm3/s");
  add("fill_rate", number_string(planner.fill_rate(), 3) + " mm3/s (constant extruder rate of the passes)");
  add("wall_rate", number_string(planner.wall_rate(), 3) + " mm3/s");
  add("base", o.base_wall ? "a wall at wall_speed" : "a bead at fill_rate");
  add("min_speed", number_string(o.min_speed, 3) + " mm/s");
  add("max_speed", number_string(o.max_speed, 3) + " mm/s");
  add("min_pass_width", number_string(o.min_pass_width, 3) + " mm");
  add("max_pass_width", number_string(o.max_pass_width, 3) + " mm");
  add("resolution", number_string(o.resolution, 3) + " mm");
  add("first_layer_factor", number_string(o.first_layer_factor, 3));
  add("center", number_string(o.center_x, 3) + "," + number_string(o.center_y, 3) + " mm");
  add("nozzle_temp", number_string(options.nozzle_temp, 3) + " C");
  add("bed_temp", number_string(options.bed_temp, 3) + " C");
  add("travel_speed", number_string(options.travel_speed, 3) + " mm/s");
  add("retract", number_string(options.retract_length, 5) + " mm at " + number_string(options.retract_speed, 3) +
                     " mm/s, travel over " + number_string(options.retract_min_travel, 3) + " mm");
  add("fan", std::to_string(options.fan));
  add("start", options.start_code.empty() ? "built-in Marlin" : (options.start_name.empty() ? "given" : options.start_name));
  add("end", options.end_code.empty() ? "built-in Marlin" : (options.end_name.empty() ? "given" : options.end_name));
  return p;
}

namespace {

// The first pass over the layers: the totals for the header. `head` ends
// where the last layer ends, as the second pass finds it.
void add_up_layers(const LithophanePlanner& planner, LithoLayer& layer, Point& head, LithoGcodeStats& stats) {
  for (int i = 0; i < planner.layer_count(); ++i) {
    plan_ordered_layer(planner, i, layer, head);
    stats.volume += layer.stats.volume;
    stats.pieces += layer.stats.pieces;
    stats.clamped_fast += layer.stats.clamped_fast;
    stats.clamped_slow += layer.stats.clamped_slow;
  }
  stats.filament = stats.volume / planner.filament_area();
}

// Cura's header (time, filament, the part's box) and the parameters.
void write_header(Emitter& e, const LithophanePlanner& planner, const LithoGcodeOptions& options,
                  const LithoGcodeStats& stats, const BedBounds& bounds) {
  e.line(";FLAVOR:Marlin");
  if (options.estimated_seconds > 0) e.line(fmt::format(";TIME:{}", std::lround(options.estimated_seconds)));
  e.line(fmt::format(";Filament used: {}m", number_string(stats.filament / 1000, 5)));
  e.line(fmt::format(";Layer height: {}", number_string(planner.options().layer_height, 3)));
  e.line(fmt::format(";MINX:{}", number_string(bounds.min_x, 3)));
  e.line(fmt::format(";MINY:{}", number_string(bounds.min_y, 3)));
  e.line(fmt::format(";MINZ:{}", number_string(planner.layer_z(0), 3)));
  e.line(fmt::format(";MAXX:{}", number_string(bounds.max_x, 3)));
  e.line(fmt::format(";MAXY:{}", number_string(bounds.max_y, 3)));
  e.line(fmt::format(";MAXZ:{}", number_string(planner.layer_z(planner.layer_count() - 1), 3)));
  e.line("");
  e.line(fmt::format(";Generated with gc-litho {}: a lithophane in variable-width passes at a constant extruder rate",
                     kVersion));
  for (const std::string& p : litho_parameters(planner, options)) e.line(";  " + p);
  e.line(fmt::format(";  pieces = {}, clamped to max speed = {}, to min speed = {}", stats.pieces, stats.clamped_fast,
                     stats.clamped_slow));
}

// The built-in start: heat, home, then a purge line 5 mm in front of the
// part at first-layer height; or the user's, with the modes the layers need.
void write_start(Emitter& e, const LithophanePlanner& planner, const LithoGcodeOptions& options,
                 const BedBounds& bounds) {
  if (!options.start_code.empty()) {
    e.text() += with_final_newline(options.start_code);
    e.set_position({bounds.min_x, bounds.min_y - 5}, 5);  // unknown: make the first layer travel explicitly
    e.line("G90");
    e.line("M83 ; relative extrusion: each E below is one piece's filament");
    return;
  }
  const LithoOptions& o = planner.options();
  MarlinStart start{.nozzle_temp = options.nozzle_temp, .bed_temp = options.bed_temp,
                    .travel_speed = options.travel_speed, .purge_x0 = bounds.min_x,
                    .purge_x1 = std::max(bounds.max_x, bounds.min_x + 20), .purge_y = bounds.min_y - 5,
                    .purge_z = planner.layer_z(0), .e_decimals = kE};
  start.purge_filament =
      o.line_width * o.layer_height * (start.purge_x1 - start.purge_x0) * 1.2 / planner.filament_area();
  e.text() += marlin_start_code(start);
  e.set_position({start.purge_x1, start.purge_y}, planner.layer_z(0));
}

// The built-in end (retract, lift, heaters and fan off, motors off) or the user's.
void write_end(Emitter& e, const LithophanePlanner& planner, const LithoGcodeOptions& options) {
  if (!options.end_code.empty()) {
    e.text() += with_final_newline(options.end_code);
    return;
  }
  e.retract(true);
  e.text() += marlin_end_code(std::max(e.z() + 10, planner.layer_z(planner.layer_count() - 1) + 10));
}

}  // namespace

LithoGcodeStats write_litho_gcode(const LithophanePlanner& planner, const LithoGcodeOptions& options,
                                  const TextOut& out) {
  options.validate();
  LithoGcodeStats stats;
  stats.layers = planner.layer_count();
  LithoLayer layer;
  Point head;  // where each layer ends, for the next one's order (path_order.hpp)
  add_up_layers(planner, layer, head, stats);
  auto emit = [&](std::string& text) {
    stats.bytes += text.size();
    out(text);
    text.clear();
  };
  Emitter e(options, planner.filament_area(), planner.options().layer_height);
  const BedBounds bounds = litho_bounds(planner);
  write_header(e, planner, options, stats, bounds);
  write_start(e, planner, options, bounds);
  e.line(fmt::format(";LAYER_COUNT:{}", planner.layer_count()));
  emit(e.text());
  for (int i = 0; i < planner.layer_count(); ++i) {
    plan_ordered_layer(planner, i, layer, head);
    e.line(fmt::format(";LAYER:{}", i));
    if (i == 1 && options.fan > 0) e.line(fmt::format("M106 S{}", options.fan));
    e.new_layer();
    for (const Path& p : layer.paths) e.path(p, layer.z);
    emit(e.text());
  }
  stats.filament = e.filament_written();
  stats.volume = stats.filament * planner.filament_area();
  write_end(e, planner, options);
  emit(e.text());
  return stats;
}

}  // namespace gcode::litho
