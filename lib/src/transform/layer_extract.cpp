#include "gcode/transform/layer_extract.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace gcode {

LayerExtractor::LayerExtractor(Selector selected, const Precision& precision, ExtractOptions options)
    : selected_(std::move(selected)), precision_(precision), options_(std::move(options)) {}

void LayerExtractor::layer(const LayerInfo& info, const MachineState& before, Emitter& out) {
  bool keep = selected_(info);
  if (!keep) {
    if (!skipped_) {
      // Every line before this one was written: the printer is here.
      printed_ = before;
      first_skipped_ = info.index;
    }
    last_skipped_ = info.index;
    skipped_ = true;
  } else {
    ++written_;
    if (skipped_) write_bridge(before, true, out);
  }
  keep_ = keep;
  out.layer(info, before);
}

void LayerExtractor::end_code(const EndCodeInfo& info, const MachineState& before, Emitter& out) {
  if (skipped_) write_bridge(before, false, out);
  keep_ = true;
  out.end_code(info, before);
}

void LayerExtractor::write_bridge(const MachineState& target, bool travel, Emitter& out) {
  out.insert(last_skipped_ == first_skipped_
                 ? fmt::format("; {}layer {} left out", options_.note_prefix, first_skipped_)
                 : fmt::format("; {}layers {}-{} left out", options_.note_prefix, first_skipped_, last_skipped_));
  skipped_ = false;
  // The E coordinate, where the next layer's numbers are absolute, or become
  // so at its next G90 (Marlin's relative E that came with G91).
  if (!target.relative_e || (target.relative_xyz && target.e_follows_g90))
    out.insert(builder_.start("G92").fixed('E', target.at(kE)).view());
  if (target.firmware_retracted != printed_.firmware_retracted) out.insert(target.firmware_retracted ? "G10" : "G11");
  // The modes the left-out layers switched: the next layer's numbers are
  // written for them (Marlin's G90/G91 set the E mode too).
  bool printer_e = printed_.relative_e;
  if (target.relative_xyz != printed_.relative_xyz) {
    out.insert(target.relative_xyz ? "G91" : "G90");
    if (target.e_follows_g90) printer_e = target.relative_xyz;
  }
  if (target.relative_e != printer_e) out.insert(target.relative_e ? "M83" : "M82");
  // Temperatures and the fan they set (Cura's fan comes on at layer 2; a
  // temperature tower changes every few layers); set, not waited for.
  for (std::size_t i = 0; i < target.hotend_target.size(); ++i) {
    if (target.hotend_target[i] == printed_.hotend_target[i]) continue;
    builder_.start("M104");
    if (static_cast<int>(i) != target.tool) builder_.word('T', static_cast<double>(i), 0);
    out.insert(builder_.word('S', target.hotend_target[i], 1).view());
  }
  if (target.bed_target != printed_.bed_target) out.insert(builder_.start("M140").word('S', target.bed_target, 1).view());
  if (target.fan != printed_.fan)
    out.insert(target.fan > 0 ? builder_.start("M106").word('S', target.fan, 1).view() : std::string_view("M107"));
  if (!travel || target.relative_xyz || !target.known[kX] || !target.known[kY] || !target.known[kZ]) return;
  // Above both heights: the last one printed and the one to come.
  Fixed z = target.at(kZ);
  Fixed top = printed_.known[kZ] ? std::max(z, printed_.at(kZ)) : z;
  Fixed lift = (top + Fixed::from_double(options_.lift_mm)).rounded(precision_.of('Z'));
  const int fd = precision_.of('F');
  out.insert(builder_.start("G0").fixed('Z', lift).word('F', options_.z_feedrate, fd).view());
  out.insert(builder_.start("G0").fixed('X', target.at(kX)).fixed('Y', target.at(kY)).word('F', options_.travel_feedrate, fd).view());
  out.insert(builder_.start("G0").fixed('Z', z).word('F', options_.z_feedrate, fd).view());
  if (target.feedrate > 0) out.insert(builder_.start("G1").fixed('F', Fixed::from_double(target.feedrate)).view());
}

void LayerExtractor::line(const TrackedLine& t, Emitter& out) {
  if (keep_) out.pass(t);
}

}  // namespace gcode
