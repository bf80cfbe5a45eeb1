#include "gcode/transform/pause_stage.hpp"

#include <algorithm>
#include <stdexcept>

#include "gcode/core/placeholders.hpp"

namespace gcode {

namespace {

std::string layers_text(int n) { return std::to_string(n) + (n == 1 ? " layer" : " layers"); }

}  // namespace

bool PauseTriggers::at_layer(int index, double z) {
  bool hit = false;
  if (before && before->contains(index)) {
    hit = true;
    ++fired_before_;
  }
  if (after && index > 1 && after->contains(index - 1)) {
    hit = true;
    ++fired_after_;
  }
  if (every > 0 && index > 1 && (index - 1) % every == 0) {
    hit = true;
    ++fired_every_;
  }
  height_used_.resize(heights.size(), false);
  for (std::size_t i = 0; i < heights.size(); ++i) {
    if (!height_used_[i] && z > heights[i] + 1e-6) {
      height_used_[i] = true;
      hit = true;
    }
  }
  return hit;
}

bool PauseTriggers::after_last(int layers) {
  if (after && layers > 0 && after->contains(layers)) {
    ++fired_after_;
    return true;
  }
  return false;
}

void PauseTriggers::verify(int layers, double top_layer_z) const {
  if (layers == 0) throw std::runtime_error("no layers found: the input is empty or prints nothing");
  if (before && (before->highest_named() > layers || fired_before_ == 0))
    throw std::runtime_error("--before-layer " + before->text() + ": no such layer, the file has " + layers_text(layers));
  if (after && (after->highest_named() > layers || fired_after_ == 0))
    throw std::runtime_error("--after-layer " + after->text() + ": no such layer, the file has " + layers_text(layers));
  if (every > 0 && fired_every_ == 0)
    throw std::runtime_error("--every " + std::to_string(every) + ": the file has only " + layers_text(layers) +
                             ", so no pause");
  for (std::size_t i = 0; i < heights.size(); ++i)
    if (i >= height_used_.size() || !height_used_[i])
      throw std::runtime_error("--z " + number_string(heights[i], 3) +
                               ": no layer starts above that height (the top layer is at Z " +
                               number_string(top_layer_z, 3) + ")");
}

void PauseTriggers::check_heights(const PrintArea& area) const {
  if (!area.has_print_top) return;
  for (double h : heights)
    if (h >= area.print_top)
      throw std::runtime_error("--z " + number_string(h, 3) + ": the print is only " +
                               number_string(area.print_top, 3) + " mm high");
}

std::string pause_table(const std::vector<PlacedPause>& pauses) {
  std::string out = "# layer\tz\tline\tpark\n";
  for (const PlacedPause& p : pauses)
    out += (p.layer > 0 ? std::to_string(p.layer) : std::string("end")) + "\t" + number_string(p.z, 3) + "\t" +
           std::to_string(p.line) + "\tX" + number_string(p.park_x, 3) + " Y" + number_string(p.park_y, 3) + " Z" +
           number_string(p.park_z, 3) + "\n";
  return out;
}

PauseStage::PauseStage(PauseTriggers& triggers, ParkRules park, PauseConfig config, const Precision& precision,
                       Diagnostics& diagnostics, std::string note_prefix)
    : triggers_(triggers),
      park_(std::move(park)),
      config_(std::move(config)),
      precision_(precision),
      diag_(diagnostics),
      note_(std::move(note_prefix)) {
  park_.check();
}

void PauseStage::layer(const LayerInfo& info, const MachineState& before, Emitter& out) {
  layers_ = info.index;
  top_layer_z_ = std::max(top_layer_z_, info.z);
  if (triggers_.at_layer(info.index, info.z)) pause(info.index, info.z, info.first_line, before, out);
  out.layer(info, before);
}

void PauseStage::end_code(const EndCodeInfo& info, const MachineState& before, Emitter& out) {
  if (triggers_.after_last(layers_)) pause(0, before.position[kZ], info.first_line, before, out);
  out.end_code(info, before);
}

void PauseStage::line(const TrackedLine& t, Emitter& out) {
  context_.observe(t);
  out.pass(t);
}

void PauseStage::pause(int layer, double z, std::uint64_t line, const MachineState& before, Emitter& out) {
  PauseConfig c = config_;
  try {
    park_.place(context_, precision_, c);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("line " + std::to_string(line) + ": " + e.what());
  }
  Placeholders values{{"layer", layer > 0 ? std::to_string(layer) : std::string("end")}, {"z", number_string(z, 3)}};
  for (std::string* text : {&c.message, &c.host_message, &c.before_wait, &c.after_wait, &c.custom_wait})
    *text = expand_placeholders(*text, values);
  PauseBlock block;
  try {
    block = build_pause(context_.point(before, &precision_), c);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("line " + std::to_string(line) + ": " + e.what());
  }
  pauses_.push_back(PlacedPause{layer, z, line, c.park_x, c.park_y, block.park_z});
  std::string where = layer > 0 ? "before layer " + std::to_string(layer) : std::string("after the last layer");
  diag_.info("pause " + where + " (Z " + number_string(z, 3) + ") at line " + std::to_string(line));
  if (dry_run_) return;
  out.insert("; " + note_ + "pause " + where + " (Z " + number_string(z, 3) + ")");
  for (const std::string& l : block.pause) out.insert(l);
  out.insert("; " + note_ + "resume");
  for (const std::string& l : block.resume) out.insert(l);
  out.insert("; " + note_ + "end");
}

}  // namespace gcode
