#include "gcode/litho/texture_stage.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "gcode/core/number.hpp"

namespace gcode::litho {

namespace {

// A command that changes what E means or uses the E position: the output's
// E must be the input's again before it.
bool uses_e(const TrackedLine& t) {
  const Line& line = t.line;
  if (line.is('M', 82) || line.is('M', 83)) return true;
  return t.move.kind != MoveKind::None && t.move.kind != MoveKind::SetPosition && line.has('E');
}

}  // namespace

TextureStage::TextureStage(const TextureProjection& projection, const GreyImage& image, const SpeedMapping& speeds,
                           double skip_z, const Precision& precision, LayerSelection* selection,
                           std::vector<std::string> header)
    : projection_(projection),
      image_(image),
      speeds_(speeds),
      skip_z_(skip_z),
      precision_(precision),
      selection_(selection),
      header_(std::move(header)) {}

void TextureStage::close_layer() {
  if (layer_high_ < layer_low_) return;
  ++stats_.layers;
  // A spiral wall climbs a whole layer height within its layer; flat layers do not climb at all.
  if (layer_high_ - layer_low_ > 0.05) ++stats_.spiral_layers;
  layer_high_ = -1;
}

void TextureStage::finish(Emitter& out) {
  close_layer();
  (void)out;
}

void TextureStage::layer(const LayerInfo& info, const MachineState& before, Emitter& out) {
  close_layer();
  if (selection_ != nullptr) selection_->enter_layer(info);
  out.layer(info, before);
}

void TextureStage::end_code(const EndCodeInfo& info, const MachineState& before, Emitter& out) {
  close_layer();
  if (selection_ != nullptr) selection_->enter_end_code();
  out.end_code(info, before);
}

void TextureStage::write_header(Emitter& out) {
  header_written_ = true;
  for (const std::string& h : header_) out.insert("; " + h);
}

void TextureStage::resync(const TrackedLine& t, Emitter& out) {
  builder_.start("G92").fixed('E', t.before.exact[kE], std::max(precision_.of('E'), 1)).comment("; gc-litho: E back in step");
  out.insert(builder_.view());
  e_offset_ = Fixed();
  ++stats_.resyncs;
}

void TextureStage::line(const TrackedLine& t, Emitter& out) {
  const Line& line = t.line;
  if (!header_written_ && line.kind != CommandKind::None) write_header(out);
  if (texture(t, out)) return;
  const Move& m = t.move;
  if (!e_offset_.is_zero()) {
    if (m.kind == MoveKind::SetPosition && (line.has('E') || !(line.has('X') || line.has('Y') || line.has('Z')))) {
      e_offset_ = Fixed();  // the input sets E itself
    } else if (uses_e(t)) {
      resync(t, out);
    }
  }
  const bool motion = m.kind == MoveKind::Linear || m.kind == MoveKind::Arc;
  if (motion && out_feed_ >= 0 && !line.has('F') && out_feed_ != t.state.feedrate) {
    // The textured run left the machine at another F: the input's own F
    // goes back on a line of its own, so the move itself stays the input's.
    builder_.start("G1").fixed('F', Fixed::from_double(t.state.feedrate), precision_.of('F'))
        .comment("; gc-litho: speed back");
    out.insert(builder_.view());
    ++stats_.restores;
    out_feed_ = -1;
    out.pass(t);
    return;
  }
  if (line.has('F') || motion) out_feed_ = -1;  // the output runs at the input's F again
  out.pass(t);
}

bool TextureStage::texture(const TrackedLine& t, Emitter& out) {
  const Move& m = t.move;
  const Line& line = t.line;
  if (m.kind != MoveKind::Linear || !m.extruding || m.ignored || m.xy_length <= 0) return false;
  if (selection_ != nullptr && !selection_->selects(t)) return false;
  if (layer_high_ < layer_low_) {
    layer_low_ = layer_high_ = m.end[kZ];
  } else {
    layer_low_ = std::min(layer_low_, m.end[kZ]);
    layer_high_ = std::max(layer_high_, m.end[kZ]);
  }
  if (std::min(m.start[kZ], m.end[kZ]) < skip_z_ - 1e-9) return false;
  ++stats_.extrusions;
  if (line.has_line_number || line.has_checksum || t.state.inches || !(m.feedrate > 0)) return false;
  const Vec3 a{m.start[kX], m.start[kY], m.start[kZ]}, b{m.end[kX], m.end[kY], m.end[kZ]};
  // One step: the Subdivider already cut the move to the resolution, so the
  // piece's pixel is the one under its middle.
  texture_move(projection_, image_, speeds_, a, b, m.feedrate / 60, m.length + 1, pieces_);
  if (pieces_.empty() || !pieces_.front().textured) {
    ++stats_.outside;
    return false;
  }
  const int f_decimals = precision_.of('F');
  const Fixed feed = Fixed::from_double(pieces_.front().speed * 60).rounded(f_decimals);
  // E per second is kept with the speed as written.
  const double factor = m.feedrate / feed.to_double();
  const int e_decimals = std::max(precision_.of('E'), 1);
  const double delta = m.end[kE] - m.start[kE];
  Fixed e_word;
  if (t.before.relative_e) {
    const double wanted = delta * factor + e_carry_;
    e_word = Fixed::from_double(wanted).rounded(e_decimals);
    e_carry_ = wanted - e_word.to_double();
  } else {
    const Fixed out_before = t.before.exact[kE] + e_offset_;
    e_word = (out_before + Fixed::from_double(delta * factor)).rounded(e_decimals);
    e_offset_ = e_word - t.state.exact[kE];
  }
  const double running = out_feed_ < 0 ? t.before.feedrate : out_feed_;
  const bool write_feed = line.has('F') || running != feed.to_double();
  builder_.start(line.command);
  for (const Word& w : line) {
    if (w.letter == 'E') {
      builder_.fixed('E', e_word, e_decimals);
    } else if (w.letter == 'F') {
      builder_.fixed('F', feed, f_decimals);
    } else {
      builder_.raw_word(w.letter, w.raw);
    }
  }
  if (write_feed && !line.has('F')) builder_.fixed('F', feed, f_decimals);
  builder_.comment(line.comment);
  out.replace(t, builder_.view());
  if (write_feed) ++stats_.speed_words;
  out_feed_ = feed.to_double();
  const double speed = feed.to_double() / 60;
  stats_.slowest = stats_.textured == 0 ? speed : std::min(stats_.slowest, speed);
  stats_.fastest = std::max(stats_.fastest, speed);
  ++stats_.textured;
  return true;
}

std::vector<std::string> texture_parameters(const std::string& image_name, const GreyImage& image,
                                            const TextureProjection& projection, const SpeedMapping& speeds,
                                            double resolution, double skip_z, const std::string& types) {
  const TextureMapping& m = projection.mapping();
  std::vector<std::string> lines;
  lines.push_back("gc-litho --texture: speed from the picture at a constant extruder rate (E x old/new speed)");
  lines.push_back(fmt::format("  image = {} ({} x {} pixels)", image_name, image.width(), image.height()));
  lines.push_back(fmt::format("  projection = {}", projection_name(m.projection)));
  const bool round = m.projection == Projection::Cylinder || m.projection == Projection::Sphere;
  lines.push_back(fmt::format("  center = {} {}{}", number_string(m.center_x, 3), number_string(m.center_y, 3),
                              m.projection == Projection::Sphere ? " " + number_string(m.center_z, 3) : std::string()));
  if (m.projection != Projection::Sphere && m.projection != Projection::Z)
    lines.push_back(fmt::format("  bottom = {} mm", number_string(m.bottom_z, 3)));
  lines.push_back(fmt::format("  offset = {} {} mm", number_string(m.offset_u, 3), number_string(m.offset_v, 3)));
  if (projection.width() > 0)
    lines.push_back(fmt::format("  size = {} x {} mm{}", number_string(projection.width(), 3),
                                number_string(projection.height(), 3), round ? " (width: once around)" : ""));
  if (speeds.binary) {
    lines.push_back(fmt::format("  binary = {} (grey below: {} mm/s, above: {} mm/s, ratio {})",
                                number_string(speeds.threshold, 3), number_string(speeds.high * speeds.ratio, 3),
                                number_string(speeds.high, 3), number_string(speeds.ratio, 3)));
  } else {
    lines.push_back(fmt::format("  speed = {} mm/s (black) to {} mm/s (white)", number_string(speeds.low, 3),
                                number_string(speeds.high, 3)));
  }
  if (speeds.invert) lines.push_back("  invert = yes (light = slow)");
  lines.push_back(fmt::format("  resolution = {} mm", number_string(resolution, 3)));
  if (skip_z > 0) lines.push_back(fmt::format("  skip_z = {} mm", number_string(skip_z, 3)));
  if (!types.empty()) lines.push_back(fmt::format("  types = {}", types));
  return lines;
}

}  // namespace gcode::litho
