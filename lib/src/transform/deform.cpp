#include "gcode/transform/deform.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "gcode/core/arc.hpp"
#include "gcode/core/diagnostics.hpp"
#include "gcode/core/line_edit.hpp"
#include "gcode/core/number.hpp"

namespace gcode {

namespace {

// mm of input: an image still off its chord over so short a piece is a jump
// (a cusp such as sqrt(|y|) still settles above it).
constexpr double kMinPiece = 1e-6;
constexpr int kMaxDepth = 40;
constexpr std::size_t kMaxPieces = 1'000'000;
constexpr double kDrop = 0.1;            // mm below what earlier layers printed
constexpr double kCell = 0.5;            // mm, the cells of what was printed
constexpr double kSame = 1e-9;           // mm or factor: the map leaves it alone
constexpr std::size_t kSectionWarnings = 5;
constexpr double kSlack = 1e-6;          // of the section's limits: 0.3 z gives 0.3 by a difference
constexpr double kProbe = 0.2;           // mm of input between the points a piece is checked at

double distance(const Point3& a, const Point3& b) { return std::hypot(a.x - b.x, a.y - b.y, a.z - b.z); }

double distance_to_chord(const Point3& p, const Point3& a, const Point3& b) {
  const double d[3] = {b.x - a.x, b.y - a.y, b.z - a.z}, q[3] = {p.x - a.x, p.y - a.y, p.z - a.z};
  const double len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const double t = len2 > 0 ? std::clamp((q[0] * d[0] + q[1] * d[1] + q[2] * d[2]) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(q[0] - t * d[0], q[1] - t * d[1], q[2] - t * d[2]);
}

bool finite(const Point3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

double coordinate(const Point3& p, int axis) { return axis == 0 ? p.x : (axis == 1 ? p.y : p.z); }

}  // namespace

void DeformOptions::validate() const {
  auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  auto zero_or_more = [](double v) { return std::isfinite(v) && v >= 0; };
  if (!positive(tolerance) || tolerance < 0.002)
    throw std::invalid_argument("--tolerance must be at least 0.002 mm (twice what 3 decimals may round)");
  if (!zero_or_more(max_speed)) throw std::invalid_argument("--max-speed must be 0 (none) or above");
  if (!zero_or_more(max_flow)) throw std::invalid_argument("--max-flow must be 0 (none) or above");
  if (!positive(filament_diameter)) throw std::invalid_argument("--filament-diameter must be above 0");
}

Deformer::Deformer(DeformMap& map, const DeformOptions& options, const Precision& precision, Diagnostics* diagnostics)
    : map_(map), options_(options), precision_(precision), diagnostics_(diagnostics),
      printed_(kCell), filament_area_(std::numbers::pi * options.filament_diameter * options.filament_diameter / 4) {
  options_.validate();
  stats_.section_min = stats_.speed_min = std::numeric_limits<double>::infinity();
  stats_.section_max = stats_.speed_max = -std::numeric_limits<double>::infinity();
}

void Deformer::refuse(std::uint64_t line, const std::string& why) const {
  throw DeformError(fmt::format("line {}: {}", line, why));
}

void Deformer::layer(const LayerInfo& info, const MachineState& before, Emitter& out) {
  printed_.next_layer();
  out.layer(info, before);
}

void Deformer::line(const TrackedLine& t, Emitter& out) {
  const Move& m = t.move;
  const bool motion = (m.kind == MoveKind::Linear || m.kind == MoveKind::Arc) && !m.ignored && !t.line.malformed;
  const double s = path_;
  path_ += m.length;
  if (motion && t.region == Region::Layer && t.state.inches && !options_.force && !leaves_alone(t, s))
    refuse(t.raw.number, "the layers move in inches (G20), which gc-deform does not bend (convert the file to "
                         "millimetres; --force passes these moves unchanged)");
  if (!motion || t.region != Region::Layer || t.state.inches || t.line.has_line_number || t.line.has_checksum ||
      !(m.length > 0) || !plan(t, s)) {
    // A move of the layers that goes nowhere ("G1 Z0.6" where Z is 0.6) stays where the output is.
    pass_outside(t, out, motion && t.region == Region::Layer && !t.state.inches);
    return;
  }
  const Point3 mid = on_move(0.5);
  map_.set_context(t.layer, s + length_ / 2);
  const bool same = moved_ <= kSame && in_step(t) && std::fabs(map_.section(mid) - 1) <= kSame &&
                    std::fabs(map_.speed(mid) - 1) <= kSame;
  entered_ = true;
  if (same) {
    ++stats_.unchanged;
    if (m.extruding) printed_.add(to_.x, to_.y, to_.z);
    out.pass(t);
    follow(t);
    return;
  }
  write(t, out);
}

// An inch move is passed as it is; that is right only where the map leaves
// its end, its cross-section and its speed alone (the identity on a G20 file).
bool Deformer::leaves_alone(const TrackedLine& t, double s) {
  const Point3 end{t.move.end[kX], t.move.end[kY], t.move.end[kZ]};
  map_.set_context(t.layer, s + t.move.length);
  return distance(map_.apply(end), end) <= kSame && std::fabs(map_.section(end) - 1) <= kSame &&
         std::fabs(map_.speed(end) - 1) <= kSame;
}

Point3 Deformer::on_move(double t) const {
  if (arc_) {
    const double a = arc_a0_ + arc_sweep_ * t;
    return {arc_cx_ + arc_r_ * std::cos(a), arc_cy_ + arc_r_ * std::sin(a), from_.z + (to_.z - from_.z) * t};
  }
  return {from_.x + (to_.x - from_.x) * t, from_.y + (to_.y - from_.y) * t, from_.z + (to_.z - from_.z) * t};
}

Point3 Deformer::image_at(double t) {
  const Point3 p = on_move(t);
  map_.set_context(layer_, s0_ + length_ * t);
  const Point3 q = map_.apply(p);
  moved_ = std::max(moved_, distance(p, q));
  if (!finite(q)) refuse(line_, "the formulas give no number here (NaN or infinite)");
  return q;
}

// Cuts [t0, t1] until the images of probe points (at least three, at most
// kProbe mm of input apart, so a wiggle shorter than the piece is seen too)
// lie within the tolerance of the chord of its ends' images, and its
// halves' images are as long as each other within it.
void Deformer::cut(double t0, const Point3& a, double t1, const Point3& b, int depth) {
  const double span = (t1 - t0) * length_;
  const int n = std::max(3, static_cast<int>(std::ceil(span / kProbe))) | 1;  // odd: the middle is a probe
  Point3 middle;
  double worst = 0;
  for (int k = 1; k <= n; ++k) {
    const Point3 q = image_at(t0 + (t1 - t0) * k / (n + 1));
    worst = std::max(worst, distance_to_chord(q, a, b));
    if (2 * k == n + 1) middle = q;
  }
  // A jump along the chord leaves every image on it, but one half of the
  // piece then carries all of it; a smooth map evens the halves out as they shrink.
  worst = std::max(worst, std::fabs(distance(a, middle) - distance(middle, b)));
  if (worst <= cut_tolerance_) {
    pieces_.push_back({t1, b});
    return;
  }
  if (span < kMinPiece || depth >= kMaxDepth || pieces_.size() >= kMaxPieces) {
    jumped_ = true;
    pieces_.push_back({t1, b});
    return;
  }
  const double tm = (t0 + t1) / 2;
  cut(t0, a, tm, middle, depth + 1);
  cut(tm, middle, t1, b, depth + 1);
}

bool Deformer::plan(const TrackedLine& t, double s) {
  const Move& m = t.move;
  from_ = {m.start[kX], m.start[kY], m.start[kZ]};
  to_ = {m.end[kX], m.end[kY], m.end[kZ]};
  arc_ = m.kind == MoveKind::Arc;
  int spans = 1;
  if (arc_) {
    const Arc a = make_arc(t.line, from_.x, from_.y, to_.x, to_.y);
    if (!a.valid || !std::isfinite(a.radius)) return false;
    arc_cx_ = a.cx, arc_cy_ = a.cy, arc_r_ = a.radius, arc_a0_ = a.start_angle, arc_sweep_ = a.sweep;
    spans = std::max(1, static_cast<int>(std::ceil(std::fabs(a.sweep) / (std::numbers::pi / 4))));
  }
  s0_ = s, length_ = m.length, layer_ = t.layer, line_ = t.raw.number;
  moved_ = 0, jumped_ = false;
  pieces_.clear();
  const int finest = std::min({precision_.of('X'), precision_.of('Y'), precision_.of('Z')});
  const double slack = 0.5 * std::sqrt(3.0) * std::pow(10.0, -finest);
  cut_tolerance_ = std::max(options_.tolerance - slack, options_.tolerance / 2);
  // A move the slicer put off the bed on purpose (Prusa's prime line at Y -3) is not the deformation's doing.
  on_bed_ = on_bed(from_) && on_bed(to_);
  start_image_ = image_at(0);
  Point3 a = start_image_;
  for (int i = 1; i <= spans; ++i) {
    const Point3 b = image_at(static_cast<double>(i) / spans);
    cut(static_cast<double>(i - 1) / spans, a, static_cast<double>(i) / spans, b, 0);
    a = b;
  }
  return true;
}

// Whether the output stream stands where the input does before `t`, so
// that the line means the same in both.
bool Deformer::in_step(const TrackedLine& t) const {
  for (int a = 0; a < 3; ++a)
    if (out_xyz_[static_cast<std::size_t>(a)] != t.before.at(a)) return false;
  if (!t.before.relative_e && t.line.has('E') && out_e_ != t.before.at(kE)) return false;
  const int df = precision_.of('F');
  return t.line.has('F') || to_scaled(out_feed_, df) == to_scaled(t.before.feedrate, df);
}

void Deformer::write(const TrackedLine& t, Emitter& out) {
  const Move& m = t.move;
  ++stats_.moves;
  if (arc_) ++stats_.arcs;
  const Point3 at{out_xyz_[0].to_double(), out_xyz_[1].to_double(), out_xyz_[2].to_double()};
  if (m.extruding && (jumped_ || (entered_written_ && distance(at, start_image_) > options_.tolerance)) &&
      !options_.force)
    refuse(line_, fmt::format("the deformation jumps: neighbouring points land more than {} mm apart "
                              "(--force prints it with a travel over the gap)",
                              number_string(options_.tolerance, 3)));
  if (m.extruding && distance(at, start_image_) > options_.tolerance) travel_to(start_image_, t, out);
  entered_written_ = true;
  double total = 0;  // the image's length, to share the E of a move that pushes no filament forward
  Point3 prev = start_image_;
  for (const Piece& p : pieces_) total += distance(prev, p.image), prev = p.image;
  const double per_mm = m.filament > 0 && m.extruding ? m.filament / m.length : 0;
  shared_ = 0;
  for (std::size_t k = 0; k < pieces_.size(); ++k) write_piece(t, k, per_mm, total, out);
  stats_.pieces += pieces_.size();
}

void Deformer::write_piece(const TrackedLine& t, std::size_t k, double per_mm, double total, Emitter& out) {
  const Move& m = t.move;
  const Piece& p = pieces_[k];
  const bool last = k + 1 == pieces_.size();
  const double t0 = k == 0 ? 0 : pieces_[k - 1].t;
  const Point3 mid = on_move((t0 + p.t) / 2);
  const std::array<Fixed, 3> was = out_xyz_;
  check_along({was[0].to_double(), was[1].to_double(), was[2].to_double()}, p.image, m.extruding);
  std::string xyz = xyz_words(p.image, t.state);
  if (xyz.empty() && !last) return;  // rounds to no move: nothing to write, no length to extrude over
  double d2 = 0;
  for (int a = 0; a < 3; ++a) d2 += std::pow((out_xyz_[a] - was[a]).to_double(), 2);
  const double written = std::sqrt(d2);
  map_.set_context(t.layer, s0_ + length_ * (t0 + p.t) / 2);
  double e = 0;
  if (per_mm > 0) {
    e = per_mm * section_at(mid) * written;
  } else if (m.filament != 0 && total > 0) {
    e = last ? m.filament - shared_ : m.filament * distance(k == 0 ? start_image_ : pieces_[k - 1].image, p.image) / total;
    shared_ += e;
  }
  const double feed = piece_feed(t, e, written, mid);
  b_.start(arc_ ? std::string_view("G1") : t.line.command);
  append_feed(feed);
  b_.text(xyz);
  append_e(e, t.state, m.filament != 0);
  if (k == 0) b_.comment(comment_of(t));
  if (per_mm > 0) stats_.filament += e;
  if (last) {
    out.replace(t, b_.view());
  } else {
    out.insert(b_.view());
  }
}

std::string_view Deformer::comment_of(const TrackedLine& t) const {
  const std::string_view code = t.line.code();
  if (code.empty()) return {};
  const std::size_t end = static_cast<std::size_t>(code.data() - t.raw.text.data()) + code.size();
  std::string_view rest = t.raw.text.substr(end);
  while (!rest.empty() && (rest.front() == ' ' || rest.front() == '\t')) rest.remove_prefix(1);
  return rest;
}

void Deformer::travel_to(const Point3& p, const TrackedLine& t, Emitter& out) {
  check_point(p, false);
  b_.start("G0");
  b_.text(xyz_words(p, t.state));
  out.insert(b_.view());
}

// The X, Y and Z words that take the output to `p` in the file's mode, and
// the output's new position.
std::string Deformer::xyz_words(const Point3& p, const MachineState& s) {
  std::string words;
  char buf[kMaxNumberChars];
  for (int a = 0; a < 3; ++a) {
    const int d = precision_.of("XYZ"[a]);
    const Fixed target = Fixed::from_double(coordinate(p, a)).rounded(d);
    Fixed& now = out_xyz_[static_cast<std::size_t>(a)];
    if (target == now) continue;
    const Fixed value = s.relative_xyz ? target - now : target;
    words.push_back(' ');
    words.push_back("XYZ"[a]);
    words.append(buf, value.format(d, buf));
    now = target;
  }
  return words;
}

double Deformer::section_at(const Point3& mid) {
  double c = map_.section(mid);
  if (!std::isfinite(c)) refuse(line_, "the cross-section factor is no number here (NaN or infinite)");
  if (c <= 0 && !options_.force)
    refuse(line_, fmt::format("the cross-section factor is {:.3g} here: the layers are squashed to nothing or turn "
                              "upside down", c));
  c = std::max(c, 0.0);
  stats_.section_min = std::min(stats_.section_min, c);
  stats_.section_max = std::max(stats_.section_max, c);
  if (c < options_.section_low * (1 - kSlack) || c > options_.section_high * (1 + kSlack)) {
    if (++stats_.outside <= kSectionWarnings && diagnostics_ != nullptr)
      diagnostics_->warn(line_, fmt::format("cross-section factor {:.3g}, outside the {:g}-{:g} x of the input a "
                                            "nozzle prints well{}", c, options_.section_low, options_.section_high,
                                            stats_.outside == kSectionWarnings ? " (no more such warnings)" : ""));
  }
  return c;
}

double Deformer::piece_feed(const TrackedLine& t, double e, double length, const Point3& mid) {
  double f = t.move.feedrate;
  if (!t.move.extruding || !(f > 0)) return f;
  const double v = map_.speed(mid);
  if (!std::isfinite(v) || v <= 0) refuse(line_, fmt::format("the speed factor is {} here; it must be above 0", v));
  f *= v;
  bool capped = false;
  if (options_.max_speed > 0 && f > options_.max_speed * 60) f = options_.max_speed * 60, capped = true;
  if (options_.max_flow > 0 && e > 0 && length > 0) {
    const double flow = e * filament_area_ / length * f / 60;  // mm3/s
    if (flow > options_.max_flow) f *= options_.max_flow / flow, capped = true;
  }
  if (capped) ++stats_.capped;
  stats_.speed_min = std::min(stats_.speed_min, f / 60);
  stats_.speed_max = std::max(stats_.speed_max, f / 60);
  return f;
}

void Deformer::append_e(double e, const MachineState& s, bool word) {
  if (!word) return;
  e_target_ += e;
  const int d = precision_.of('E');
  const Fixed target = Fixed::from_double(e_target_).rounded(d);
  const Fixed value = s.relative_e ? (target - out_e_) : target;
  out_e_ = target;
  char buf[kMaxNumberChars];
  b_.text(" E").text(std::string_view(buf, value.format(d, buf)));
}

void Deformer::append_feed(double feed) {
  const int d = precision_.of('F');
  if (!(feed > 0) || to_scaled(feed, d) == to_scaled(out_feed_, d)) return;
  out_feed_ = Fixed::from_double(feed).rounded(d).to_double();
  char buf[kMaxNumberChars];
  b_.text(" F").text(std::string_view(buf, format_number(feed, d, buf)));
}

// Every quarter of a cell along a piece, so a long straight piece is seen in every cell it crosses.
void Deformer::check_along(const Point3& a, const Point3& b, bool extruding) {
  const int n = std::max(1, static_cast<int>(std::ceil(distance(a, b) / (kCell / 4))));
  for (int i = 1; i <= n; ++i) {
    const double f = static_cast<double>(i) / n;
    check_point({a.x + (b.x - a.x) * f, a.y + (b.y - a.y) * f, a.z + (b.z - a.z) * f}, extruding);
  }
}

bool Deformer::on_bed(const Point3& p) const {
  const double tol = options_.tolerance;
  return p.x >= options_.bed.min_x - tol && p.x <= options_.bed.max_x + tol && p.y >= options_.bed.min_y - tol &&
         p.y <= options_.bed.max_y + tol;
}

void Deformer::check_point(const Point3& p, bool extruding) {
  const double tol = options_.tolerance;
  if (p.z < -tol)
    refuse(line_, fmt::format("the deformation sends the nozzle below the bed (Z {})", number_string(p.z, 3)));
  if (options_.has_bed && on_bed_ && !on_bed(p))
    refuse(line_, fmt::format("the deformation leaves the bed (X {} Y {}; the bed is X {}..{} Y {}..{})",
                              number_string(p.x, 3), number_string(p.y, 3), number_string(options_.bed.min_x, 3),
                              number_string(options_.bed.max_x, 3), number_string(options_.bed.min_y, 3),
                              number_string(options_.bed.max_y, 3)));
  if (options_.has_max_z && p.z > options_.max_z + tol)
    refuse(line_, fmt::format("the deformation goes above the printer's height (Z {} > {})", number_string(p.z, 3),
                              number_string(options_.max_z, 3)));
  const double top = printed_.top(p.x, p.y, -std::numeric_limits<double>::infinity());
  if (p.z < top - kDrop - tol && !options_.force)
    refuse(line_,
           fmt::format("the deformation sends the nozzle down into what is printed (Z {} at X {} Y {}, "
                       "printed up to {} there; --force to print it anyway)",
                       number_string(p.z, 3), number_string(p.x, 3), number_string(p.y, 3), number_string(top, 3)));
  if (extruding) printed_.add(p.x, p.y, p.z);
}

// A line the deformation does not cut: passed, or with E shifted by what the
// layers' filament changed and the input's F where the output's differs.
void Deformer::pass_outside(const TrackedLine& t, Emitter& out, bool in_layers) {
  const bool move = (t.move.kind == MoveKind::Linear || t.move.kind == MoveKind::Arc) && !t.line.malformed &&
                    !t.line.has_line_number && !t.line.has_checksum;
  const bool stay = in_layers && !t.before.relative_xyz && !in_step(t);
  if (!move || (in_step_outside(t) && !stay)) {
    out.pass(t);
    follow(t);
    return;
  }
  LineEdit edit(t.line);
  if (!t.before.relative_e && t.line.has('E'))
    edit.set('E', out_e_ + (t.state.at(kE) - t.before.at(kE)), precision_.of('E'));
  const int df = precision_.of('F');
  if (!t.line.has('F') && t.state.feedrate > 0 && to_scaled(out_feed_, df) != to_scaled(t.state.feedrate, df))
    edit.set('F', Fixed::from_double(t.state.feedrate), df);
  for (int a = 0; a < 3 && stay; ++a)
    if (t.line.has("XYZ"[a])) edit.set("XYZ"[a], out_xyz_[static_cast<std::size_t>(a)], precision_.of("XYZ"[a]));
  out.replace(t, edit.text());
  if (stay) {  // the output did not move
    const std::array<Fixed, 3> at = out_xyz_;
    follow(t);
    out_xyz_ = at;
  } else {
    follow(t);
  }
}

bool Deformer::in_step_outside(const TrackedLine& t) const {
  if (!t.before.relative_e && t.line.has('E') && out_e_ != t.before.at(kE)) return false;
  const int df = precision_.of('F');
  return t.line.has('F') || !(t.state.feedrate > 0) || to_scaled(out_feed_, df) == to_scaled(t.before.feedrate, df);
}

// The output's position, E and F after a line that went out as the input
// wrote it (relative words move the output from where it is).
void Deformer::follow(const TrackedLine& t) {
  const Move& m = t.move;
  const bool homes_all = m.kind == MoveKind::Home && !t.line.has('X') && !t.line.has('Y') && !t.line.has('Z');
  for (int a = 0; a < 3; ++a) {
    Fixed& now = out_xyz_[static_cast<std::size_t>(a)];
    const bool word = t.line.has("XYZ"[a]);
    if ((m.kind == MoveKind::Linear || m.kind == MoveKind::Arc) && t.before.relative_xyz) {
      now += t.state.at(a) - t.before.at(a);
    } else if (word || homes_all) {
      now = t.state.at(a);
    }
  }
  if (m.kind == MoveKind::SetPosition && t.line.has('E')) {
    out_e_ = t.state.at(kE);
    e_target_ = out_e_.to_double();
  } else {
    out_e_ += t.state.at(kE) - t.before.at(kE);
    e_target_ += (t.state.at(kE) - t.before.at(kE)).to_double();
  }
  if (m.kind == MoveKind::Linear || m.kind == MoveKind::Arc) out_feed_ = t.state.feedrate;
}

}  // namespace gcode
