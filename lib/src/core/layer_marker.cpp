#include "gcode/core/layer_marker.hpp"

#include <re2/re2.h>

#include <stdexcept>

#include "gcode/core/number.hpp"

namespace gcode {

namespace {

bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

bool read_number(std::string_view s, double& v) { return parse_number(trim(s), v); }

// "; layer 3, Z = 0.600" (Simplify3D); "; layer end" is not a marker.
bool parse_simplify3d(std::string_view c, CommentInfo& info) {
  if (!starts_with(c, "layer ")) return false;
  std::string_view rest = c.substr(6);
  auto comma = rest.find(',');
  if (comma == std::string_view::npos) return false;
  double n = 0;
  if (!read_number(rest.substr(0, comma), n)) return false;
  auto eq = rest.find('=', comma);
  if (eq == std::string_view::npos) return false;
  double z = 0;
  if (!read_number(rest.substr(eq + 1), z)) return false;
  info.marker = MarkerKind::Simplify3D;
  info.has_number = true;
  info.number = static_cast<long>(n);
  info.has_z = true;
  info.z = z;
  return true;
}

}  // namespace

LayerMarkers::LayerMarkers() = default;
LayerMarkers::~LayerMarkers() = default;
LayerMarkers::LayerMarkers(LayerMarkers&&) noexcept = default;
LayerMarkers& LayerMarkers::operator=(LayerMarkers&&) noexcept = default;

LayerMarkers::LayerMarkers(const std::string& pattern) {
  RE2::Options options;
  options.set_log_errors(false);
  user_ = std::make_unique<re2::RE2>(pattern, options);
  if (!user_->ok()) throw std::invalid_argument("bad --layer-marker pattern: " + user_->error());
}

CommentInfo LayerMarkers::classify(std::string_view c) const {
  CommentInfo info;
  double v = 0;
  if (c.empty()) return info;
  if (user_) {
    std::string number;
    if (user_->NumberOfCapturingGroups() > 0 ? RE2::PartialMatch(c, *user_, &number)
                                             : RE2::PartialMatch(c, *user_)) {
      info.marker = MarkerKind::User;
      if (!number.empty() && parse_number(number, v)) {
        info.has_number = true;
        info.number = static_cast<long>(v);
      }
      return info;
    }
  }
  switch (c.front()) {
    case 'T':
      if (starts_with(c, "TYPE:")) {
        info.is_type = true;
        info.type = trim(c.substr(5));
      }
      return info;
    case 'L':
      if (user_) return info;
      if (starts_with(c, "LAYER_CHANGE")) {
        info.marker = MarkerKind::LayerChange;
      } else if (starts_with(c, "LAYER:") && read_number(c.substr(6), v)) {
        info.marker = MarkerKind::CuraLayer;
        info.has_number = true;
        info.number = static_cast<long>(v);
      } else if (starts_with(c, "LAYER_HEIGHT:") && read_number(c.substr(13), v)) {
        info.has_height = true;
        info.height = v;
      }
      return info;
    case 'C':
      if (!user_ && starts_with(c, "CHANGE_LAYER")) info.marker = MarkerKind::ChangeLayer;
      return info;
    case 'Z':
      if (starts_with(c, "Z:") && read_number(c.substr(2), v)) {
        info.has_z = true;
        info.z = v;
      } else if (starts_with(c, "Z_HEIGHT:") && read_number(c.substr(9), v)) {
        info.has_z = true;
        info.z = v;
      }
      return info;
    case 'H':
      if (starts_with(c, "HEIGHT:") && read_number(c.substr(7), v)) {
        info.has_height = true;
        info.height = v;
      }
      return info;
    case 'l':
      if (!user_) parse_simplify3d(c, info);
      return info;
    default:
      return info;
  }
}

}  // namespace gcode
