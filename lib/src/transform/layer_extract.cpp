#include "gcode/transform/layer_extract.hpp"

#include <algorithm>
#include <fmt/format.h>

#include <string>

namespace gcode {

LayerExtractor::LayerExtractor(OutputBuffer& out, Selector selected, ExtractOptions options)
    : out_(out), selected_(std::move(selected)), options_(options) {}

void LayerExtractor::write_line(std::string_view text) {
  out_.write(text);
  out_.write(ending_);
}

void LayerExtractor::on_layer(const LayerInfo& layer, const MachineState& before) {
  bool keep = selected_(layer);
  if (!keep) {
    if (!skipped_) first_skipped_ = layer.index;
    last_skipped_ = layer.index;
    skipped_ = true;
  } else {
    ++written_;
    if (skipped_) write_bridge(before, true);
  }
  keep_ = keep;
}

void LayerExtractor::on_end_code(std::uint64_t, std::uint64_t, const MachineState& before) {
  if (skipped_) write_bridge(before, false);
  keep_ = true;
}

void LayerExtractor::write_bridge(const MachineState& target, bool travel) {
  write_line(last_skipped_ == first_skipped_
                 ? fmt::format("; gc-layers: layer {} left out", first_skipped_)
                 : fmt::format("; gc-layers: layers {}-{} left out", first_skipped_, last_skipped_));
  skipped_ = false;
  if (!target.relative_e) write_line(builder_.start("G92").word('E', target.position[kE], precision_.of('E')).view());
  if (target.firmware_retracted != printed_fw_retracted_) write_line(target.firmware_retracted ? "G10" : "G11");
  if (!travel || target.relative_xyz || printed_relative_xyz_ || !target.known[kX] || !target.known[kY] ||
      !target.known[kZ])
    return;
  int d = precision_.of('Z');
  double top = std::max(target.position[kZ], printed_known_z_ ? printed_position_[kZ] : target.position[kZ]);
  write_line(builder_.start("G0").word('Z', top + options_.lift_mm, d).word('F', options_.z_feedrate, 0).view());
  write_line(builder_.start("G0")
                 .word('X', target.position[kX], precision_.of('X'))
                 .word('Y', target.position[kY], precision_.of('Y'))
                 .word('F', options_.travel_feedrate, 0)
                 .view());
  write_line(builder_.start("G0").word('Z', target.position[kZ], d).word('F', options_.z_feedrate, 0).view());
  if (target.feedrate > 0) write_line(builder_.start("G1").word('F', target.feedrate, precision_.of('F')).view());
}

void LayerExtractor::on_line(const TrackedLine& t) {
  if (!t.raw.ending.empty()) ending_ = t.raw.ending;
  for (const Word& w : t.line)
    if (w.has_value) precision_.observe(w.letter, w.decimals);
  if (!keep_) return;
  out_.write(t.raw.text);
  out_.write(t.raw.ending);
  if (t.move.kind != MoveKind::None) {
    printed_position_ = t.state.position;
    printed_known_z_ = t.state.known[kZ];
  }
  printed_relative_xyz_ = t.state.relative_xyz;
  printed_fw_retracted_ = t.state.firmware_retracted;
}

}  // namespace gcode
