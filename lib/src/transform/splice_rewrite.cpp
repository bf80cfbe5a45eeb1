#include "gcode/transform/splice_rewrite.hpp"

#include <algorithm>

#include "gcode/core/line_edit.hpp"

namespace gcode {

namespace {

int at_least(const Precision& p, char letter, int decimals) { return std::max(p.of(letter), decimals); }

}  // namespace

void SpliceRewrite::reset(Fixed z_shift, double extrusion_scale, bool relative_e, Fixed e) {
  shift_ = z_shift;
  scale_ = extrusion_scale;
  relative_e_ = relative_e;
  e_ = e;
  source_pushed_ = Fixed();
  output_pushed_ = Fixed();
  identity_ = shift_.is_zero() && scale_ == 1;
}

Fixed SpliceRewrite::scaled(Fixed amount, int decimals) {
  // The running total is scaled and rounded, so rounding never adds up.
  source_pushed_ += amount;
  Fixed total = Fixed::from_double(source_pushed_.to_double() * scale_).rounded(decimals);
  Fixed piece = total - output_pushed_;
  output_pushed_ = total;
  return piece;
}

bool SpliceRewrite::apply(const TrackedLine& t, const Precision& precision, std::string_view& text) {
  const Line& l = t.line;
  if (l.kind != CommandKind::Standard) return false;
  if (l.letter == 'M') {
    if (l.number == 82 || l.number == 83) relative_e_ = t.state.relative_e;
    return false;
  }
  if (l.letter != 'G' || l.subcode >= 0) return false;
  const Word* z = nullptr;
  bool need_z = false, need_e = false;
  Fixed new_e;
  switch (l.number) {
    case 0: case 1: case 2: case 3: {
      if (t.move.ignored) return false;
      z = l.find('Z');
      need_z = !shift_.is_zero() && z != nullptr && z->has_value && !t.before.relative_xyz;
      const Word* e = l.find('E');
      if (e != nullptr && e->has_value) {
        Fixed delta = t.state.at(kE) - t.before.at(kE);
        Fixed out = delta;
        if (scale_ != 1 && t.move.extruding) out = scaled(delta, precision.of('E'));
        e_ += out;
        if (relative_e_) {
          new_e = out;
          need_e = !t.before.relative_e || out != delta;
        } else {
          new_e = e_;
          need_e = t.before.relative_e || e_ != t.state.at(kE);
        }
      }
      break;
    }
    case 92: {
      z = l.find('Z');
      need_z = !shift_.is_zero() && z != nullptr && z->has_value;
      const Word* e = l.find('E');
      if (e != nullptr && e->has_value) e_ = t.state.at(kE);
      break;
    }
    case 90: case 91:
      relative_e_ = t.state.relative_e;
      return false;
    default:
      return false;
  }
  if (!need_z && !need_e) return false;
  LineEdit edit(l);
  if (need_z) edit.set('Z', z->fixed() + shift_, at_least(precision, 'Z', z->decimals));
  if (need_e) edit.set('E', new_e, at_least(precision, 'E', l.find('E')->decimals));
  text_.assign(edit.text());
  text = text_;
  return true;
}

}  // namespace gcode
