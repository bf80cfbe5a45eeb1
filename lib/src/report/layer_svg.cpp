#include "gcode/report/layer_svg.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <iterator>
#include <stdexcept>

#include "gcode/core/arc.hpp"
#include "gcode/report/estimator.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/core/number.hpp"
#include "gcode/core/placeholders.hpp"
#include "gcode/core/text.hpp"

namespace gcode {

namespace {

constexpr double kDefaultHeight = 0.2;
constexpr float kJoin = 1e-4f;  // mm: a segment continuing the last point extends its polyline

std::string lower(std::string_view s) {
  std::string r(s);
  for (char& c : r)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return r;
}


// Shortest fixed decimal, two places: 0.01 mm is finer than any nozzle.
void num(std::string& out, double v, int decimals = 2) {
  char buf[kMaxNumberChars];
  out += number_text(v, decimals, buf);
}

void add_paths(Box2& box, const std::vector<DrawnPath>& paths, bool travel) {
  for (const DrawnPath& p : paths) {
    if (p.travel && !travel) continue;
    for (std::size_t i = 0; i + 1 < p.xy.size(); i += 2) box.add(p.xy[i], p.xy[i + 1]);
  }
}

// What one picture shows: its paths with a margin (a whole bed would leave a
// small print a speck); the bed outline shows where it falls inside.
Box2 picture_box(const LayerDrawing& d, const SvgOptions& o) {
  Box2 box;
  add_paths(box, d.paths, o.travel);
  if (o.below) add_paths(box, d.below, false);
  if (box.empty())
    for (const Point2& p : o.bed) box.add(p.x, p.y);
  if (box.empty()) box.add(0, 0), box.add(10, 10);
  double margin = std::max(1.0, 0.03 * std::max(box.width(), box.depth()));
  box.min_x -= margin, box.min_y -= margin, box.max_x += margin, box.max_y += margin;
  return box;
}

std::string name_of(const SvgOptions& o, int feature) {
  if (feature < 0 || feature >= static_cast<int>(o.feature_names.size())) return "extrusion";
  return o.feature_names[static_cast<std::size_t>(feature)];
}

void polyline(std::string& out, const DrawnPath& p, bool with_width) {
  out += "<polyline";
  if (with_width) {
    out += " stroke-width=\"";
    num(out, p.width, 3);
    out += '"';
  }
  out += " points=\"";
  for (std::size_t i = 0; i + 1 < p.xy.size(); i += 2) {
    if (i) out += ' ';
    num(out, p.xy[i]);
    out += ',';
    num(out, p.xy[i + 1]);
  }
  out += "\"/>\n";
}

// The layer in bed coordinates (Y up), to be placed in a viewBox of `box`.
void layer_body(std::string& out, const LayerDrawing& d, const SvgOptions& o, const Box2& box) {
  out += "<g transform=\"matrix(1 0 0 -1 0 ";
  num(out, box.min_y + box.max_y);
  out += ")\" fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";
  double fine = std::max(box.width(), box.depth()) / 500;  // a hairline at any scale
  if (!o.bed.empty()) {
    out += "<polygon fill=\"#f6f6f2\" stroke=\"#9a9a9a\" stroke-width=\"";
    num(out, 2 * fine);
    out += "\" points=\"";
    for (std::size_t i = 0; i < o.bed.size(); ++i) {
      if (i) out += ' ';
      num(out, o.bed[i].x);
      out += ',';
      num(out, o.bed[i].y);
    }
    out += "\"/>\n";
  }
  if (o.below && !d.below.empty()) {
    out += "<g stroke=\"#d2d2d2\">\n";
    for (const DrawnPath& p : d.below) polyline(out, p, true);
    out += "</g>\n";
  }
  // Extrusions in print order; runs of one feature share a group.
  int open = -2;
  for (const DrawnPath& p : d.paths) {
    if (p.travel) continue;
    if (p.feature != open) {
      if (open != -2) out += "</g>\n";
      out += "<g stroke=\"" + feature_color(name_of(o, p.feature)) + "\">\n";
      open = p.feature;
    }
    polyline(out, p, true);
  }
  if (open != -2) out += "</g>\n";
  if (o.travel) {
    out += "<g stroke=\"#2f6fdf\" stroke-width=\"";
    num(out, fine, 3);
    out += "\" stroke-dasharray=\"";
    num(out, 6 * fine, 3);
    out += ' ';
    num(out, 4 * fine, 3);
    out += "\">\n";
    for (const DrawnPath& p : d.paths)
      if (p.travel) polyline(out, p, false);
    out += "</g>\n";
  }
  if (o.retractions && !d.retractions.empty()) {
    out += "<g fill=\"#d01010\" stroke=\"none\">\n";
    for (std::size_t i = 0; i + 1 < d.retractions.size(); i += 2) {
      out += "<circle cx=\"";
      num(out, d.retractions[i]);
      out += "\" cy=\"";
      num(out, d.retractions[i + 1]);
      out += "\" r=\"";
      num(out, std::max(0.3, 2 * fine), 3);
      out += "\"/>\n";
    }
    out += "</g>\n";
  }
  out += "</g>\n";
}

void nested_svg(std::string& out, double x, double y, double w, double h, const Box2& box) {
  fmt::format_to(std::back_inserter(out), "<svg x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" viewBox=\"", x,
                 y, w, h);
  num(out, box.min_x, 3);
  out += ' ';
  num(out, box.min_y, 3);
  out += ' ';
  num(out, box.width(), 3);
  out += ' ';
  num(out, box.depth(), 3);
  out += "\" preserveAspectRatio=\"xMidYMid meet\">\n";
}

std::string title_of(const LayerDrawing& d) {
  std::string t = fmt::format("Layer {}  Z {:.3f} mm", d.layer, d.z);
  if (d.height > 0) t += fmt::format(" (height {:.3f})", d.height);
  if (d.seconds >= 0) t += "  " + format_duration(d.seconds);
  return t;
}

void text(std::string& out, double x, double y, double size, std::string_view s, bool bold = false) {
  fmt::format_to(std::back_inserter(out), "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"{:.1f}\"{}>", x, y, size,
                 bold ? " font-weight=\"bold\"" : "");
  append_xml_text(out, s);
  out += "</text>\n";
}

// The legend: features used, then travel, retraction and the layer below.
double legend(std::string& out, double x, double y, const std::vector<int>& features, const SvgOptions& o) {
  const double row = 20, size = 13;
  text(out, x, y, size, "Legend", true);
  y += row;
  for (int f : features) {
    std::string name = name_of(o, f);
    fmt::format_to(std::back_inserter(out), "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"22\" height=\"10\" fill=\"{}\"/>\n",
                   x, y - 10, feature_color(name));
    text(out, x + 30, y, size, name);
    y += row;
  }
  if (o.travel) {
    fmt::format_to(std::back_inserter(out),
                   "<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#2f6fdf\" stroke-width=\"1.5\" "
                   "stroke-dasharray=\"4 3\"/>\n",
                   x, y - 5, x + 22, y - 5);
    text(out, x + 30, y, size, "travel");
    y += row;
  }
  if (o.retractions) {
    fmt::format_to(std::back_inserter(out), "<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"4\" fill=\"#d01010\"/>\n", x + 11,
                   y - 5);
    text(out, x + 30, y, size, "retraction");
    y += row;
  }
  if (o.below) {
    fmt::format_to(std::back_inserter(out), "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"22\" height=\"10\" fill=\"#d2d2d2\"/>\n",
                   x, y - 10);
    text(out, x + 30, y, size, "layer below");
    y += row;
  }
  return y;
}

void features_used(const LayerDrawing& d, std::vector<int>& out) {
  for (const DrawnPath& p : d.paths)
    if (!p.travel && std::find(out.begin(), out.end(), p.feature) == out.end()) out.push_back(p.feature);
}

void svg_open(std::string& out, double w, double h) {
  fmt::format_to(std::back_inserter(out),
                 "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                 "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"{:.0f}\" height=\"{:.0f}\" "
                 "viewBox=\"0 0 {:.0f} {:.0f}\" font-family=\"sans-serif\">\n"
                 "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
                 w, h, w, h);
}

}  // namespace

void append_xml_text(std::string& out, std::string_view s) {
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default:
        // Control characters are not allowed in XML 1.0.
        if (static_cast<unsigned char>(c) >= 0x20 || c == '\t') out += c;
    }
  }
}

std::string feature_color(std::string_view name) {
  std::string n = lower(name);
  auto has = [&](std::string_view k) { return n.find(k) != std::string::npos; };
  // Order matters: "External perimeter" before "perimeter", "Solid infill"
  // and "Top solid infill" before "infill".
  if (has("outer") || has("external") || has("overhang")) return "#e8541e";
  if (has("inner") || has("perimeter") || has("wall")) return "#f2b01e";
  if (has("top")) return "#d8303c";
  if (has("bridge")) return "#3c78b4";
  if (has("solid") || has("skin") || has("bottom")) return "#8e4fc2";
  if (has("gap")) return "#6b6b6b";
  if (has("interface") || has("support-interface")) return "#1b7f3a";
  if (has("support")) return "#3fbf4f";
  if (has("infill") || has("fill")) return "#a82a2a";
  if (has("skirt") || has("brim")) return "#16a08a";
  if (has("wipe") || has("prime")) return "#c8c820";
  // Anything else: a stable colour from the name.
  std::uint32_t h = 2166136261u;
  for (char c : n) h = (h ^ static_cast<unsigned char>(c)) * 16777619u;
  return fmt::format("#{:02x}{:02x}{:02x}", 60 + h % 150, 60 + (h >> 8) % 150, 60 + (h >> 16) % 150);
}

bool has_layer_placeholder(std::string_view pattern) {
  return has_placeholder(pattern, "") || has_placeholder(pattern, "layer") || pattern.find("%d") != std::string_view::npos;
}

std::string expand_layer_pattern(std::string_view pattern, int layer) {
  std::string number = std::to_string(layer);
  std::string out = expand_placeholders(pattern, {{"", number}, {"layer", number}});
  // printf style, as some users write it.
  if (std::size_t at = out.find("%d"); at != std::string::npos) out.replace(at, 2, number);
  return out;
}

LayerDrawer::LayerDrawer(std::function<bool(int)> selected, double filament_diameter)
    : selected_(std::move(selected)), filament_area_(std::numbers::pi * filament_diameter * filament_diameter / 4) {}

void LayerDrawer::layer(const LayerInfo& layer, const MachineState& before, Emitter& out) {
  out.layer(layer, before);
  close_layer();
  current_ = LayerDrawing{};
  current_.layer = layer.index;
  current_.z = layer.z;
  current_.height = layer.height;
  current_selected_ = selected_(layer.index);
  in_layer_ = true;
}

void LayerDrawer::close_layer() {
  if (!in_layer_) return;
  std::vector<DrawnPath> extrusions;
  for (DrawnPath& p : current_.paths) {
    if (p.travel) continue;
    if (current_selected_) {
      extrusions.push_back(p);
    } else {
      extrusions.push_back(std::move(p));
    }
  }
  if (current_selected_) {
    current_.below = std::move(previous_);
    done_.push_back(std::move(current_));
  }
  previous_ = std::move(extrusions);
  current_ = LayerDrawing{};
  in_layer_ = false;
}

void LayerDrawer::finish(Emitter&) { close_layer(); }

void LayerDrawer::add_segment(bool travel, int feature, float width, double x0, double y0, double x1, double y1) {
  auto fx0 = static_cast<float>(x0), fy0 = static_cast<float>(y0);
  if (!current_.paths.empty()) {
    DrawnPath& last = current_.paths.back();
    std::size_t n = last.xy.size();
    if (last.travel == travel && last.feature == feature && last.width == width && n >= 2 &&
        std::fabs(last.xy[n - 2] - fx0) < kJoin && std::fabs(last.xy[n - 1] - fy0) < kJoin) {
      last.xy.push_back(static_cast<float>(x1));
      last.xy.push_back(static_cast<float>(y1));
      return;
    }
  }
  current_.paths.push_back(DrawnPath{travel, feature, width, {fx0, fy0, static_cast<float>(x1), static_cast<float>(y1)}});
}

void LayerDrawer::line(const TrackedLine& t, Emitter& out) {
  out.pass(t);
  if (!t.line.comment.empty()) {
    std::string_view c = t.line.comment_text();
    if (c.substr(0, 6) == "WIDTH:") {
      double w = 0;
      if (parse_number(trim(c.substr(6)), w) && w > 0) width_comment_ = w;
    }
  }
  if (t.region != Region::Layer || !in_layer_) return;
  const Move& m = t.move;
  // Only the selected layer keeps travel and retractions; every layer keeps
  // its extrusions, which may become the next selected layer's "below".
  bool keep_all = current_selected_;
  if (m.kind == MoveKind::FirmwareRetract || (m.retraction() && m.kind != MoveKind::None)) {
    if (keep_all) {
      current_.retractions.push_back(static_cast<float>(m.end[kX]));
      current_.retractions.push_back(static_cast<float>(m.end[kY]));
    }
    return;
  }
  if ((m.kind != MoveKind::Linear && m.kind != MoveKind::Arc) || m.ignored || m.xy_length <= 0) return;
  bool travel = !m.extruding;
  if (travel && !keep_all) return;
  float width = 0;
  if (!travel) {
    double w = width_comment_;
    if (w <= 0) {
      double h = current_.height > 0 ? current_.height : kDefaultHeight;
      w = m.filament * filament_area_ / (m.xy_length * h);
    }
    width = static_cast<float>(std::round(std::clamp(w, 0.05, 5.0) * 100) / 100);
  }
  if (m.filament < 0 && keep_all) {  // a wipe that retracts while it moves
    current_.retractions.push_back(static_cast<float>(m.end[kX]));
    current_.retractions.push_back(static_cast<float>(m.end[kY]));
  }
  if (m.kind == MoveKind::Arc) {
    Arc arc = make_arc(t.line, m.start[kX], m.start[kY], m.end[kX], m.end[kY], t.before.inches ? kMmPerInch : 1.0);
    if (arc.valid) {
      int steps = std::clamp(static_cast<int>(arc.length_xy() / 0.5), 4, 720);
      double px = m.start[kX], py = m.start[kY];
      for (int i = 1; i <= steps; ++i) {
        double a = arc.start_angle + arc.sweep * i / steps;
        double x = i == steps ? m.end[kX] : arc.cx + arc.radius * std::cos(a);
        double y = i == steps ? m.end[kY] : arc.cy + arc.radius * std::sin(a);
        add_segment(travel, travel ? -1 : t.feature, width, px, py, x, y);
        px = x, py = y;
      }
      return;
    }
  }
  add_segment(travel, travel ? -1 : t.feature, width, m.start[kX], m.start[kY], m.end[kX], m.end[kY]);
}

std::string layer_svg(const LayerDrawing& d, const SvgOptions& o) {
  Box2 box = picture_box(d, o);
  double scale = o.size_px / std::max(box.width(), box.depth());
  double draw_w = box.width() * scale, draw_h = box.depth() * scale;
  const double title_h = 36, legend_w = 210;
  std::vector<int> features;
  features_used(d, features);
  double legend_h = 20.0 * (static_cast<double>(features.size()) + 5) + 20;
  std::string out;
  out.reserve(4096 + d.paths.size() * 64);
  svg_open(out, draw_w + legend_w, title_h + std::max(draw_h, legend_h));
  out += "<title>";
  append_xml_text(out, title_of(d));
  out += "</title>\n";
  text(out, 10, 24, 16, title_of(d), true);
  nested_svg(out, 0, title_h, draw_w, draw_h, box);
  layer_body(out, d, o, box);
  out += "</svg>\n";
  legend(out, draw_w + 16, title_h + 16, features, o);
  out += "</svg>\n";
  return out;
}

std::string layer_sheet_svg(const std::vector<LayerDrawing>& drawings, const SvgOptions& o, int columns) {
  if (drawings.empty()) throw std::invalid_argument("no layer to draw");
  // One scale for all: the union of the pictures' boxes.
  Box2 box;
  for (const LayerDrawing& d : drawings) box.add(picture_box(d, o));
  auto n = static_cast<int>(drawings.size());
  if (columns <= 0) columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  int rows = (n + columns - 1) / columns;
  double cell = std::min(o.size_px, 400.0);
  double scale = cell / std::max(box.width(), box.depth());
  double cell_w = box.width() * scale, cell_h = box.depth() * scale;
  const double title_h = 26, gap = 12, legend_w = 210;
  std::vector<int> features;
  for (const LayerDrawing& d : drawings) features_used(d, features);
  double grid_w = columns * (cell_w + gap) + gap, grid_h = rows * (cell_h + title_h + gap) + gap;
  double legend_h = 20.0 * (static_cast<double>(features.size()) + 5) + 20;
  std::string out;
  svg_open(out, grid_w + legend_w, std::max(grid_h, legend_h));
  for (int i = 0; i < n; ++i) {
    const LayerDrawing& d = drawings[static_cast<std::size_t>(i)];
    double x = gap + (i % columns) * (cell_w + gap);
    double y = gap + (i / columns) * (cell_h + title_h + gap);
    text(out, x, y + 16, 12, title_of(d), true);
    nested_svg(out, x, y + title_h, cell_w, cell_h, box);
    fmt::format_to(std::back_inserter(out),
                   "<rect x=\"{:.3f}\" y=\"{:.3f}\" width=\"{:.3f}\" height=\"{:.3f}\" fill=\"none\" stroke=\"#bbbbbb\" "
                   "stroke-width=\"{:.3f}\"/>\n",
                   box.min_x, box.min_y, box.width(), box.depth(), 1 / scale);
    layer_body(out, d, o, box);
    out += "</svg>\n";
  }
  legend(out, grid_w + 8, gap + 16, features, o);
  out += "</svg>\n";
  return out;
}

void write_layer_pictures(std::vector<LayerDrawing>& drawings, const SvgOptions& options,
                          const std::vector<double>& layer_seconds, bool sheet, const std::string& out,
                          const std::function<void(const std::string& path, const std::string& svg)>& write) {
  if (drawings.empty()) throw std::runtime_error("no layer matches the selection");
  for (LayerDrawing& d : drawings) {
    auto i = static_cast<std::size_t>(d.layer - 1);
    d.seconds = i < layer_seconds.size() ? layer_seconds[i] : -1;
  }
  if (sheet) {
    write(out, layer_sheet_svg(drawings, options));
    return;
  }
  if (drawings.size() > 1 && !has_layer_placeholder(out))
    throw std::runtime_error("several layers selected: give --svg-out a pattern such as layer-{}.svg");
  for (const LayerDrawing& d : drawings) write(expand_layer_pattern(out, d.layer), layer_svg(d, options));
}

}  // namespace gcode
