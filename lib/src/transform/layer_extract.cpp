#include "gcode/transform/layer_extract.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <vector>

#include "gcode/transform/transition.hpp"

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
  std::vector<std::string> lines;
  Transition t(printed_, precision_, lines,
               {.lift = options_.lift_mm, .z_feed = options_.z_feedrate, .xy_feed = options_.travel_feedrate});
  // The E coordinate, where the next layer's numbers are absolute, or become
  // so at its next G90 (Marlin's relative E that came with G91).
  if (!target.relative_e || (target.relative_xyz && target.e_follows_g90)) t.e_coordinate(target.at(kE), true);
  t.firmware_retraction(target.firmware_retracted);
  // The modes the left-out layers switched: the next layer's numbers are
  // written for them (Marlin's G90/G91 set the E mode too).
  bool printer_e = printed_.relative_e;
  if (target.relative_xyz != printed_.relative_xyz) {
    t.positioning(target.relative_xyz);
    if (target.e_follows_g90) printer_e = target.relative_xyz;
  }
  if (target.relative_e != printer_e) t.e_mode(target.relative_e, true);
  // Temperatures and the fan they set (Cura's fan comes on at layer 2; a
  // temperature tower changes every few layers); set, not waited for.
  for (std::size_t i = 0; i < target.hotend_target.size(); ++i)
    if (target.hotend_target[i] != printed_.hotend_target[i])
      t.hotend(static_cast<int>(i), target.hotend_target[i], false, static_cast<int>(i) != target.tool);
  if (target.bed_target != printed_.bed_target) t.bed(target.bed_target, false);
  if (target.fan != printed_.fan) t.fan(target.fan);
  if (travel && !target.relative_xyz && target.known[kX] && target.known[kY] && target.known[kZ]) {
    // Above both heights: the last one printed and the one to come.
    Fixed z = target.at(kZ);
    t.move_z(t.safe_z(printed_.known[kZ] ? std::max(z, printed_.at(kZ)) : z));
    t.move_xy(target.at(kX), target.at(kY));
    t.move_z(z);
    t.feed_rate(target.feedrate, true);
  }
  for (const std::string& l : lines) out.insert(l);
}

void LayerExtractor::line(const TrackedLine& t, Emitter& out) {
  if (keep_) out.pass(t);
}

}  // namespace gcode
