#include "gcode/transform/layer_extract.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace gcode {

LayerExtractor::LayerExtractor(Selector selected, const Precision& precision, ExtractOptions options)
    : selected_(std::move(selected)), precision_(precision), options_(std::move(options)) {}

void LayerExtractor::layer(const LayerInfo& info, const MachineState& before, Emitter& out) {
  if (!printed_any_) {
    // Nothing written yet (no start code): the printer is where the file starts.
    printed_relative_xyz_ = before.relative_xyz;
    printed_relative_e_ = before.relative_e;
    printed_fw_retracted_ = before.firmware_retracted;
    printed_any_ = true;
  }
  bool keep = selected_(info);
  if (!keep) {
    if (!skipped_) first_skipped_ = info.index;
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
  if (!target.relative_e) out.insert(builder_.start("G92").fixed('E', target.at(kE)).view());
  if (target.firmware_retracted != printed_fw_retracted_) out.insert(target.firmware_retracted ? "G10" : "G11");
  // The modes the left-out layers switched: the next layer's numbers are
  // written for them (Marlin's G90/G91 set the E mode too).
  bool printer_e = printed_relative_e_;
  if (target.relative_xyz != printed_relative_xyz_) {
    out.insert(target.relative_xyz ? "G91" : "G90");
    if (target.e_follows_g90) printer_e = target.relative_xyz;
  }
  if (target.relative_e != printer_e) out.insert(target.relative_e ? "M83" : "M82");
  if (!travel || target.relative_xyz || !target.known[kX] || !target.known[kY] || !target.known[kZ]) return;
  // Above both heights: the last one printed and the one to come.
  Fixed z = target.at(kZ);
  Fixed top = printed_known_z_ ? std::max(z, Fixed::from_double(printed_position_[kZ])) : z;
  Fixed lift = (top + Fixed::from_double(options_.lift_mm)).rounded(precision_.of('Z'));
  const int fd = precision_.of('F');
  out.insert(builder_.start("G0").fixed('Z', lift).word('F', options_.z_feedrate, fd).view());
  out.insert(builder_.start("G0").fixed('X', target.at(kX)).fixed('Y', target.at(kY)).word('F', options_.travel_feedrate, fd).view());
  out.insert(builder_.start("G0").fixed('Z', z).word('F', options_.z_feedrate, fd).view());
  if (target.feedrate > 0) out.insert(builder_.start("G1").fixed('F', Fixed::from_double(target.feedrate)).view());
}

void LayerExtractor::line(const TrackedLine& t, Emitter& out) {
  if (!keep_) return;
  out.pass(t);
  if (t.move.kind != MoveKind::None) {
    printed_position_ = t.state.position;
    printed_known_z_ = t.state.known[kZ];
  }
  printed_any_ = true;
  printed_relative_xyz_ = t.state.relative_xyz;
  printed_relative_e_ = t.state.relative_e;
  printed_fw_retracted_ = t.state.firmware_retracted;
}

}  // namespace gcode
