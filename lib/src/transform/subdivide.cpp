#include "gcode/transform/subdivide.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <cstring>
#include <stdexcept>
#include <string>

#include "gcode/core/arc.hpp"
#include "gcode/core/diagnostics.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/core/number.hpp"

namespace gcode {

namespace {

constexpr double kDecimalScale[] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11};
// Beyond this a coordinate is junk (X1e300), not a position: such a move is
// passed through rather than cut into astronomically many pieces.
constexpr double kMaxCoordinate = 1e6;
constexpr double kMaxPieces = 1e7;
// Room for the command and six numbers of a piece.
constexpr std::size_t kPieceBuffer = 64 + 8 * (kMaxNumberChars + 2);

int axis_of(char letter) {
  switch (letter) {
    case 'X': return kX;
    case 'Y': return kY;
    case 'Z': return kZ;
    case 'E': return kE;
    default: return -1;
  }
}

}  // namespace

void SubdivideOptions::validate() const {
  auto bad = [](double v) { return !std::isfinite(v) || v < 0; };
  if (bad(max_length)) throw std::invalid_argument("--max must be a length in mm above 0");
  if (bad(latency)) throw std::invalid_argument("--latency must be a time in seconds above 0");
  if (bad(max_rate)) throw std::invalid_argument("--max-rate must be a number of lines per second above 0");
  if (bad(min_length)) throw std::invalid_argument("--min must be a length in mm, 0 or more");
  if (!std::isfinite(arc_tolerance) || arc_tolerance <= 0)
    throw std::invalid_argument("--arc-tolerance must be a length in mm above 0");
  if (buffer < 1) throw std::invalid_argument("--buffer must be at least 1");
  if (max_length > 0 && latency > 0) throw std::invalid_argument("choose one limit: --max or --latency, not both");
  if (max_length > 0 && max_length < 2 * min_length)
    throw std::invalid_argument("--max " + number_string(max_length, 3) + " is below twice --min " +
                                number_string(min_length, 3) +
                                ": a move just over the limit is cut in two pieces of half the limit, which "
                                "would be shorter than --min; lower --min");
}

double SubdivideOptions::piece_limit(double feedrate, bool* rate_won) const {
  double limit = 0;
  if (max_length > 0) {
    limit = max_length;
  } else if (latency > 0) {
    // Without a feed rate there is no time budget to share out.
    if (!(feedrate > 0)) return 0;
    limit = feedrate / 60.0 * latency / buffer;
    if (limit < 2 * min_length) limit = 2 * min_length;
  } else {
    return 0;
  }
  if (max_rate > 0 && feedrate > 0) {
    // A piece takes length/speed seconds; the link carries max_rate lines/s.
    double floor = feedrate / 60.0 / max_rate;
    if (floor > limit) {
      limit = floor;
      if (rate_won != nullptr) *rate_won = true;
    }
  }
  return limit;
}

// Per axis: where the move starts and ends in the file's own units (inches
// under G20), and how to write it.
struct AxisPlan {
  bool write = false;
  bool relative = false;
  int decimals = 3;
  double start = 0;
  double end = 0;
  std::string_view raw;     // the input's text; empty when the line did not write the axis
  std::int64_t total = 0;   // relative: the written amount in units of 10^-decimals
};

struct Subdivider::Plan {
  std::array<AxisPlan, 4> axes{};
  std::array<char, 8> order{};  // letters to write, in the input's order
  int letters = 0;
  std::string_view feed;   // raw F text, on the first piece only
  std::string_view command;
  std::uint64_t pieces = 0;
  bool arc = false;
  Arc geometry;             // in file units
};

Subdivider::Subdivider(const SubdivideOptions& options, const Precision& precision, Diagnostics* diagnostics,
                       LayerSelection* selection)
    : options_(options), precision_(precision), diagnostics_(diagnostics), selection_(selection) {}

void Subdivider::warn(std::uint64_t line_number, std::string_view message) {
  if (diagnostics_ != nullptr) diagnostics_->warn(line_number, message);
}

void Subdivider::layer(const LayerInfo& info, const MachineState& before, Emitter& out) {
  if (selection_ != nullptr) selection_->enter_layer(info);
  out.layer(info, before);
}

void Subdivider::end_code(const EndCodeInfo& info, const MachineState& before, Emitter& out) {
  if (selection_ != nullptr) selection_->enter_end_code();
  out.end_code(info, before);
}

void Subdivider::line(const TrackedLine& t, Emitter& out) {
  if (t.origin == LineOrigin::Input) ++stats_.lines;
  const Line& line = t.line;
  if (line.malformed) {
    // Firmware-specific M codes with quoted text (Prusa's M862.3 P "MK3S") are
    // none of our business; an unreadable move or junk is worth a word.
    if (line.kind != CommandKind::Standard || line.letter == 'G')
      warn(t.raw.number, "cannot read this line; passed through unchanged");
  } else if (t.move.kind == MoveKind::Linear || t.move.kind == MoveKind::Arc) {
    PieceLimit limit;
    if ((selection_ == nullptr || selection_->selects(t)) && wants_cut(t, limit)) {
      // Made only here: a Plan is 300 bytes to clear, and most moves of a
      // file stay whole (gc-subdivide --max 1000 on the bench's 160 MB file:
      // 0.54 -> 0.47 s).
      Plan plan;
      if (plan_move(t, limit, plan)) {
        write_pieces(t, plan, out);
        return;
      }
    }
  }
  out.pass(t);
}

bool Subdivider::wants_cut(const TrackedLine& t, PieceLimit& limit) const {
  const Line& line = t.line;
  const Move& move = t.move;
  bool arc = move.kind == MoveKind::Arc;
  if (move.ignored) return false;
  if (arc ? !options_.split_arcs : move.xy_length <= 0) return false;  // pure Z or E moves stay whole
  bool limited = options_.split_travel || !move.travel;
  limit.mm = limited ? options_.piece_limit(move.feedrate, &limit.rate_won) : 0;
  if (!arc && !(move.length > limit.mm && limit.mm > 0)) return false;
  // A numbered or checksummed line cannot be cut without breaking its checksum.
  return !(line.has_line_number || line.has_checksum || line.command.size() > 16);
}

bool Subdivider::plan_move(const TrackedLine& t, const PieceLimit& piece_limit, Plan& plan) {
  const Line& line = t.line;
  const Move& move = t.move;
  const bool arc = move.kind == MoveKind::Arc;
  const double limit = piece_limit.mm;
  const bool rate_won = piece_limit.rate_won;
  if (!plan_axes(t, plan) || !plan_words(t, plan)) return false;
  int finest = plan_decimals(t, plan);
  if (finest < 0) return false;

  // Rounding each written point moves it by up to half a unit per axis; keep
  // that much below the limit so the written pieces stay within it.
  double scale = t.state.inches ? kMmPerInch : 1.0;
  double slack = 1.8 / kDecimalScale[finest] * scale;
  double effective = limit - slack;
  if (effective < limit / 2) effective = limit / 2;

  double pieces = 1;
  if (arc) {
    pieces = plan_arc(t, plan, limit, effective);
    if (pieces < 0) return false;
  } else {
    pieces = std::ceil(move.length / effective);
    plan.command = line.command;
  }
  if (!(pieces <= kMaxPieces)) {
    warn(t.raw.number, "move too long to cut into pieces; passed through unchanged");
    return false;
  }
  plan.pieces = pieces < 1 ? 1 : static_cast<std::uint64_t>(pieces);
  if (rate_won) warn_rate_once(t, limit);
  return true;
}

// Where each axis starts and ends, in the file's units; false (with a
// warning) for a coordinate no printer has.
bool Subdivider::plan_axes(const TrackedLine& t, Plan& plan) {
  const Move& move = t.move;
  const MachineState& after = t.state;
  double scale = after.inches ? kMmPerInch : 1.0;
  for (int a = 0; a < 4; ++a) {
    AxisPlan& p = plan.axes[static_cast<std::size_t>(a)];
    p.relative = a == kE ? after.relative_e : after.relative_xyz;
    p.start = move.start[a] / scale;
    p.end = move.end[a] / scale;
    if (!std::isfinite(p.start) || !std::isfinite(p.end) || std::fabs(p.start) > kMaxCoordinate ||
        std::fabs(p.end) > kMaxCoordinate) {
      warn(t.raw.number, "a coordinate out of any printer's range; move passed through unchanged");
      return false;
    }
  }
  return true;
}

// The words the pieces write, in the input's order; false for a word that
// is not ours to cut or a letter written twice.
bool Subdivider::plan_words(const TrackedLine& t, Plan& plan) {
  const bool arc = t.move.kind == MoveKind::Arc;
  for (const Word& w : t.line) {
    if (!w.has_value) return false;
    // P: Marlin's extra turns, cut like the rest of the sweep.
    if (arc && (w.letter == 'I' || w.letter == 'J' || w.letter == 'R' || w.letter == 'P')) continue;
    int a = axis_of(w.letter);
    if (a < 0 && w.letter != 'F') return false;  // S (laser), T ...: not ours to cut
    for (int i = 0; i < plan.letters; ++i)
      if (plan.order[static_cast<std::size_t>(i)] == w.letter) return false;  // "G1 X1 X2": ambiguous
    plan.order[static_cast<std::size_t>(plan.letters++)] = w.letter;
    if (w.letter == 'F') {
      plan.feed = w.raw;
      continue;
    }
    AxisPlan& p = plan.axes[static_cast<std::size_t>(a)];
    p.write = true;
    p.raw = w.raw;
  }
  return true;
}

// Each axis's decimals and a relative axis's amount; returns the finest
// decimals of the written XYZ axes, or -1 when an amount is too large.
int Subdivider::plan_decimals(const TrackedLine& t, Plan& plan) const {
  const bool arc = t.move.kind == MoveKind::Arc;
  int inch_digits = t.state.inches ? 2 : 0;  // 0.001 in is 0.025 mm: too coarse for a point on the line
  int finest = 9;
  for (int a = 0; a < 4; ++a) {
    AxisPlan& p = plan.axes[static_cast<std::size_t>(a)];
    char letter = "XYZE"[a];
    int d = precision_.of(letter) + inch_digits;
    if (!p.raw.empty()) d = std::max(d, decimals_of(p.raw) + inch_digits);
    p.decimals = std::min(d, 9);
    if (p.relative) {
      double amount = p.raw.empty() ? 0.0 : t.line.value_or(letter, 0);
      double units = amount * kDecimalScale[p.decimals];
      if (!(std::fabs(units) < 9e15)) return -1;
      p.total = to_scaled(amount, p.decimals);
    }
    if (a != kE && (p.write || arc)) finest = std::min(finest, p.decimals);
  }
  return finest;
}

// An arc's chords: how many (within the tolerance, and the length limit),
// and the words each writes. -1 (with a warning) for an arc that is none.
double Subdivider::plan_arc(const TrackedLine& t, Plan& plan, double limit, double effective) {
  double scale = t.state.inches ? kMmPerInch : 1.0;
  const AxisPlan& x = plan.axes[kX];
  const AxisPlan& y = plan.axes[kY];
  plan.geometry = make_arc(t.line, x.start, y.start, x.end, y.end);
  if (!plan.geometry.valid || !std::isfinite(plan.geometry.radius) || plan.geometry.radius * scale > kMaxCoordinate) {
    warn(t.raw.number, "not a valid arc; passed through unchanged");
    return -1;
  }
  double sweep = std::fabs(plan.geometry.sweep);
  double radius_mm = plan.geometry.radius * scale;
  double dz = (plan.axes[kZ].end - plan.axes[kZ].start) * scale;
  double length = std::hypot(radius_mm * sweep, dz);
  // A chord of angle t deviates r(1 - cos(t/2)) from its arc; never more than a quarter turn.
  double max_angle = std::numbers::pi / 2;
  if (options_.arc_tolerance < radius_mm)
    max_angle = std::min(max_angle, 2 * std::acos(1 - options_.arc_tolerance / radius_mm));
  double pieces = std::ceil(sweep / max_angle);
  if (limit > 0) pieces = std::max(pieces, std::ceil(length / effective));
  for (int a = 0; a < 2; ++a) plan.axes[static_cast<std::size_t>(a)].write = true;
  plan.arc = true;
  // Chords carry X and Y always, then whatever else the arc wrote.
  std::array<char, 8> order{'X', 'Y'};
  int n = 2;
  for (int k = 0; k < plan.letters; ++k) {
    char c = plan.order[static_cast<std::size_t>(k)];
    if (c != 'X' && c != 'Y') order[static_cast<std::size_t>(n++)] = c;
  }
  plan.order = order;
  plan.letters = n;
  plan.command = "G1";
  return pieces;
}

// --max-rate made the pieces longer than the limit asked: said once.
void Subdivider::warn_rate_once(const TrackedLine& t, double limit) {
  if (warned_rate_ || diagnostics_ == nullptr) return;
  warned_rate_ = true;
  diagnostics_->warn(t.raw.number, "--max-rate asks for pieces of " + number_string(limit, 3) + " mm at F" +
                                       number_string(t.move.feedrate, 0) +
                                       ", longer than the limit; honouring the rate (warned once)");
}

void Subdivider::write_pieces(const TrackedLine& t, const Plan& plan, Emitter& out) {
  const RawLine& raw = t.raw;
  const Line& line = t.line;
  ++stats_.moves_split;
  if (plan.arc) ++stats_.arcs;
  stats_.pieces += plan.pieces;
  // The bytes after the code: spacing and comment, kept on the first piece.
  std::string_view code = line.code();
  std::size_t code_end = static_cast<std::size_t>(code.data() - raw.text.data()) + code.size();
  std::string_view rest = code.empty() ? std::string_view{} : raw.text.substr(code_end);

  std::array<std::int64_t, 4> done{};  // relative axes: units written so far
  const double n = static_cast<double>(plan.pieces);
  char buffer[kPieceBuffer];
  for (std::uint64_t k = 1; k <= plan.pieces; ++k) {
    bool last = k == plan.pieces;
    double frac = static_cast<double>(k) / n;
    double cx = 0, cy = 0;
    if (plan.arc && !last) {
      double angle = plan.geometry.start_angle + plan.geometry.sweep * frac;
      cx = plan.geometry.cx + plan.geometry.radius * std::cos(angle);
      cy = plan.geometry.cy + plan.geometry.radius * std::sin(angle);
    }
    char* p = buffer;
    std::memcpy(p, plan.command.data(), plan.command.size());
    p += plan.command.size();
    for (int i = 0; i < plan.letters; ++i) {
      char letter = plan.order[static_cast<std::size_t>(i)];
      if (letter == 'F') {
        if (k != 1 || plan.feed.size() > kMaxNumberChars) continue;
        *p++ = ' ';
        *p++ = 'F';
        std::memcpy(p, plan.feed.data(), plan.feed.size());
        p += plan.feed.size();
        continue;
      }
      int a = axis_of(letter);
      const AxisPlan& ax = plan.axes[static_cast<std::size_t>(a)];
      *p++ = ' ';
      *p++ = letter;
      if (ax.relative) {
        std::int64_t target = ax.total;
        if (!last) {
          double at = ax.start + (ax.end - ax.start) * frac;
          if (plan.arc && a == kX) at = cx;
          if (plan.arc && a == kY) at = cy;
          target = to_scaled(at - ax.start, ax.decimals);
        }
        std::int64_t step = target - done[static_cast<std::size_t>(a)];
        done[static_cast<std::size_t>(a)] = target;
        p += format_scaled(step, ax.decimals, p);
      } else if (last && !ax.raw.empty() && ax.raw.size() < kMaxNumberChars) {
        std::memcpy(p, ax.raw.data(), ax.raw.size());
        p += ax.raw.size();
      } else {
        double at = last ? ax.end : ax.start + (ax.end - ax.start) * frac;
        if (plan.arc && !last && a == kX) at = cx;
        if (plan.arc && !last && a == kY) at = cy;
        p += format_number(at, ax.decimals, p);
      }
    }
    std::string_view piece(buffer, static_cast<std::size_t>(p - buffer));
    if (k == 1 && !rest.empty()) {
      // The comment (any length) stays on the first piece.
      scratch_.assign(piece);
      scratch_.append(rest);
      piece = scratch_;
    }
    // The last piece takes the input line's place (and its ending, also a
    // missing final one); the others are new lines.
    if (last) {
      out.replace(t, piece);
    } else {
      out.insert(piece);
    }
  }
}

}  // namespace gcode
