#include "gcode/core/layer_marker.hpp"

#include <re2/re2.h>

#include <stdexcept>

#include "gcode/core/line.hpp"
#include "gcode/core/number.hpp"
#include "gcode/core/text.hpp"

namespace gcode {

namespace {

bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }

bool read_number(std::string_view s, double& v) { return parse_number(trim(s), v); }

void skip_blanks(std::string_view& s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
}

bool skip(std::string_view& s, std::string_view prefix) {
  if (!starts_with(s, prefix)) return false;
  s.remove_prefix(prefix.size());
  return true;
}

// Reads the number at the front of `s` ("0.25 @ 2" -> 0.25) and drops it.
bool take_number(std::string_view& s, double& v) {
  std::size_t n = 0;
  if (n < s.size() && (s[n] == '-' || s[n] == '+')) ++n;
  while (n < s.size() && ((s[n] >= '0' && s[n] <= '9') || s[n] == '.')) ++n;
  if (!parse_number(s.substr(0, n), v)) return false;
  s.remove_prefix(n);
  return true;
}

// A layer number in range of a long (junk like "LAYER:1e300" is no number).
bool in_layer_range(double v) { return v > -1e15 && v < 1e15; }

// A layer number: a whole number at the front of `s`, dropped from it.
bool take_layer_number(std::string_view& s, long& number) {
  double v = 0;
  std::string_view rest = s;
  if (!take_number(rest, v) || !in_layer_range(v) || v != static_cast<double>(static_cast<long>(v))) return false;
  number = static_cast<long>(v);
  s = rest;
  return true;
}

void set_number(CommentInfo& info, long n) {
  info.has_number = true;
  info.number = n;
}
void set_z(CommentInfo& info, double z) {
  info.has_z = true;
  info.z = z;
}
void set_height(CommentInfo& info, double h) {
  info.has_height = true;
  info.height = h;
}

// "; layer 3, Z = 0.600" (Simplify3D); "; layer end" is not a marker.
bool parse_simplify3d(std::string_view c, CommentInfo& info) {
  if (!skip(c, "layer ")) return false;
  long n = 0;
  if (!take_layer_number(c, n) || !skip(c, ",")) return false;
  auto eq = c.find('=');
  double z = 0;
  if (eq == std::string_view::npos || !read_number(c.substr(eq + 1), z)) return false;
  info.marker = MarkerKind::Simplify3D;
  set_number(info, n);
  set_z(info, z);
  return true;
}

// "; BEGIN_LAYER_OBJECT z=0.263 z_thickness=0.263" (KISSlicer; 1.1 writes
// only z=). The layer's Z comes in the first travel after it.
bool parse_kisslicer(std::string_view c, CommentInfo& info) {
  if (!skip(c, "BEGIN_LAYER_OBJECT")) return false;
  info.marker = MarkerKind::KISSlicer;
  double v = 0;
  skip_blanks(c);
  if (skip(c, "z=") && take_number(c, v)) set_z(info, v);
  skip_blanks(c);
  if (skip(c, "z_thickness=") && take_number(c, v)) set_height(info, v);
  return true;
}

// ";; --- layer 12 (0.200 @ 2.6) ---" (Kiri:Moto, written when the device
// has no layer G-code): 0-based number, layer height, Z. Before the Z move.
bool parse_kiri_moto(std::string_view c, CommentInfo& info) {
  c.remove_prefix(1);  // the second ';'
  skip_blanks(c);
  long n = 0;
  if (!skip(c, "--- layer ") || !take_layer_number(c, n)) return false;
  info.marker = MarkerKind::KiriMoto;
  set_number(info, n);
  double height = 0, z = 0;
  skip_blanks(c);
  if (!skip(c, "(") || !take_number(c, height)) return true;
  skip_blanks(c);
  if (!skip(c, "@")) return true;
  skip_blanks(c);
  if (!take_number(c, z)) return true;
  set_height(info, height);
  set_z(info, z);
  return true;
}

// "(<layer> 0.4 )" (Skeinforge, SFACT): the layer's Z.
bool parse_skeinforge(std::string_view c, CommentInfo& info) {
  if (!skip(c, "<layer>")) return false;
  skip_blanks(c);
  double z = 0;
  if (!take_number(c, z)) return false;
  info.marker = MarkerKind::Skeinforge;
  set_z(info, z);
  return true;
}

// "(Slice 0, 1 Extruder)" (Miracle-Grue, MakerWare's engine): 0-based.
bool parse_miracle_grue(std::string_view c, CommentInfo& info) {
  long n = 0;
  if (!skip(c, "Slice ") || !take_layer_number(c, n) || !skip(c, ",")) return false;
  info.marker = MarkerKind::MiracleGrue;
  set_number(info, n);
  return true;
}

// A built-in marker parser, unless a user pattern replaces the built-in markers.
CommentInfo built_in(bool enabled, bool (*parse)(std::string_view, CommentInfo&), std::string_view c,
                     CommentInfo& info) {
  if (enabled) parse(c, info);
  return info;
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
      if (!number.empty() && parse_number(number, v) && in_layer_range(v)) {
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
      } else if (starts_with(c, "LAYER:") && read_number(c.substr(6), v) && in_layer_range(v)) {
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
    // Markers with a syntax of their own, by their first character.
    case 'l': return built_in(!user_, parse_simplify3d, c, info);
    case 'B': return built_in(!user_, parse_kisslicer, c, info);
    case ';': return built_in(!user_, parse_kiri_moto, c, info);
    case '<': return built_in(!user_, parse_skeinforge, c, info);
    case 'S': return built_in(!user_, parse_miracle_grue, c, info);
    default:
      return info;
  }
}


CommentInfo LayerMarkers::classify_move(std::string_view c) const {
  CommentInfo info;
  // Most moves carry no comment or a feature one ("; perimeter"): one byte decides.
  if (user_ || c.empty() || c.front() != 'm' || !skip(c, "move to next layer")) return info;
  info.marker = MarkerKind::LayerMove;
  skip_blanks(c);
  long n = 0;
  if (skip(c, "(") && take_layer_number(c, n) && skip(c, ")")) set_number(info, n);
  return info;
}

bool LayerMarkers::marks_layer(std::string_view text) const {
  if (text.find(';') == std::string_view::npos && text.find('(') == std::string_view::npos) return false;
  const Line line = Line::parse(text);
  if (line.comment.empty()) return false;
  if (line.kind == CommandKind::None) return classify(line.comment_text()).marker != MarkerKind::None;
  return line.is_move() && classify_move(line.comment_text()).marker != MarkerKind::None;
}

void LayerMarkerSearch::feed(std::string_view block) {
  std::size_t pos = 0;
  for (std::size_t nl; !found_ && (nl = block.find('\n', pos)) != std::string_view::npos; pos = nl + 1) {
    std::string_view line = block.substr(pos, nl - pos);
    if (cut_.empty()) {
      look(line);
    } else {
      if (cut_.size() < kLongestLine) cut_.append(line.substr(0, kLongestLine - cut_.size()));
      look(cut_);
      cut_.clear();
    }
  }
  if (!found_ && pos < block.size() && cut_.size() < kLongestLine)
    cut_.append(block.substr(pos, kLongestLine - cut_.size()));
}

void LayerMarkerSearch::look(std::string_view line) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  found_ = markers_.marks_layer(line);
}

}  // namespace gcode
