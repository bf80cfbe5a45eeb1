#include "gcode/objects/object_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>

#include "gcode/report/layer_report.hpp"
#include "gcode/report/layer_svg.hpp"

namespace gcode {

namespace {

std::string box_text(const Box2& b) {
  if (b.empty()) return "-";
  return fmt::format("({:.1f},{:.1f})-({:.1f},{:.1f})", b.min_x, b.min_y, b.max_x, b.max_y);
}

// Distinct colours for neighbouring objects.
std::string colour(std::size_t i) {
  static const char* const kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf",
                                         "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22"};
  return kColours[i % std::size(kColours)];
}

}  // namespace

const char* source_name(ObjectSource s) { return s == ObjectSource::Footprint ? "footprint" : "labels"; }

std::string object_table_text(const ObjectTable& table, const std::string& file_name) {
  std::string out;
  auto to = std::back_inserter(out);
  const bool footprints = !table.objects.empty() && table.objects.front().source == ObjectSource::Footprint;
  fmt::format_to(to, "# {}: {} object{} ({})\n", file_name, table.objects.size(), table.objects.size() == 1 ? "" : "s",
                 footprints ? "from footprints" : fmt::format("{} labels", dialect_name(table.dialect)));
  std::size_t id_w = 2, name_w = 4;
  for (const PlateObject& o : table.objects) {
    id_w = std::max(id_w, o.id.size());
    name_w = std::max(name_w, o.name.size());
  }
  fmt::format_to(to, "{:<{}}  {:<{}}  {:>7}  {:<29}  {:>11}  {:>8}  {}\n", "id", id_w, "name", name_w, "layers", "box (mm)",
                 "filament_mm", "time_s", "source");
  for (const PlateObject& o : table.objects)
    fmt::format_to(to, "{:<{}}  {:<{}}  {:>7}  {:<29}  {:>11.1f}  {:>8.0f}  {}\n", o.id, id_w, o.name, name_w,
                   o.first_layer == 0 ? std::string("-") : fmt::format("{}-{}", o.first_layer, o.last_layer), box_text(o.box),
                   o.filament_mm, o.time_s, source_name(o.source));
  if (table.outside.filament_mm > 0) {
    std::string features;
    for (const std::string& f : table.outside.features) features += (features.empty() ? "" : ",") + f;
    fmt::format_to(to, "# outside every object: {:.1f} mm of filament, {:.0f} s{}{}\n", table.outside.filament_mm,
                   table.outside.time_s, features.empty() ? "" : ": ", features);
  }
  return out;
}

std::string object_table_json(const ObjectTable& table) {
  std::string out = "{\"objects\": [";
  auto to = std::back_inserter(out);
  for (std::size_t i = 0; i < table.objects.size(); ++i) {
    const PlateObject& o = table.objects[i];
    out += i == 0 ? "\n  {\"id\": " : ",\n  {\"id\": ";
    append_json_string(out, o.id);
    out += ", \"name\": ";
    append_json_string(out, o.name);
    if (o.box.empty()) {
      out += ", \"bbox\": null";
    } else {
      fmt::format_to(to, ", \"bbox\": [{:.3f}, {:.3f}, {:.3f}, {:.3f}]", o.box.min_x, o.box.min_y, o.box.max_x, o.box.max_y);
    }
    out += ", \"polygon\": [";
    for (std::size_t p = 0; p < o.outline.size(); ++p)
      fmt::format_to(to, "{}[{:.3f}, {:.3f}]", p == 0 ? "" : ", ", o.outline[p].x, o.outline[p].y);
    fmt::format_to(to, "], \"first_layer\": {}, \"last_layer\": {}, \"filament_mm\": {:.3f}, \"time_s\": {:.1f}, \"source\": \"{}\"}}",
                   o.first_layer, o.last_layer, o.filament_mm, o.time_s, source_name(o.source));
  }
  fmt::format_to(to, "{}], \"outside\": {{\"filament_mm\": {:.3f}, \"time_s\": {:.1f}, \"features\": [", table.objects.empty() ? "" : "\n",
                 table.outside.filament_mm, table.outside.time_s);
  for (std::size_t f = 0; f < table.outside.features.size(); ++f) {
    if (f > 0) out += ", ";
    append_json_string(out, table.outside.features[f]);
  }
  out += "]}}\n";
  return out;
}

std::string object_table_svg(const ObjectTable& table, const Polygon& bed, int size_px) {
  Box2 view;
  for (const Point2& p : bed) view.add(p.x, p.y);
  for (const PlateObject& o : table.objects) view.add(o.box);
  if (view.empty()) view = Box2{0, 0, 1, 1};
  const double margin = 5;
  const double w = view.width() + 2 * margin, h = view.depth() + 2 * margin;
  const double scale = size_px / std::max(w, h);
  std::string out;
  auto to = std::back_inserter(out);
  fmt::format_to(to,
                 "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{:.0f}\" height=\"{:.0f}\" viewBox=\"{:.2f} {:.2f} {:.2f} {:.2f}\">\n",
                 w * scale, h * scale, view.min_x - margin, -(view.max_y + margin), w, h);
  // Y up as on the printer: the picture's y is the printer's -Y.
  auto points = [&](const Polygon& poly) {
    std::string s;
    for (const Point2& p : poly) s += fmt::format("{:.2f},{:.2f} ", p.x, -p.y);
    return s;
  };
  if (bed.size() >= 3)
    fmt::format_to(to, "<polygon points=\"{}\" fill=\"#f6f6f2\" stroke=\"#9a9a9a\" stroke-width=\"{:.2f}\"/>\n", points(bed), 1 / scale);
  // Numbers that fit the smallest object, and are readable on the whole bed.
  double font = std::min(w, h) / 40;
  for (const PlateObject& o : table.objects)
    if (!o.box.empty()) font = std::min(font, 0.6 * std::min(o.box.width(), o.box.depth()));
  font = std::max(font, std::min(w, h) / 120);
  for (std::size_t i = 0; i < table.objects.size(); ++i) {
    const PlateObject& o = table.objects[i];
    if (o.outline.size() < 3) continue;
    out += "<g><title>";
    append_xml_text(out, o.id + " " + o.name);
    fmt::format_to(to, "</title><polygon points=\"{}\" fill=\"{}\" fill-opacity=\"0.25\" stroke=\"{}\" stroke-width=\"{:.2f}\"/>\n",
                   points(o.outline), colour(i), colour(i), 2 / scale);
    const Point2 c = o.box.centre();
    fmt::format_to(to, "<text x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"{:.2f}\" font-family=\"sans-serif\" text-anchor=\"middle\" dominant-baseline=\"middle\">",
                   c.x, -c.y, font);
    append_xml_text(out, o.id);
    out += "</text></g>\n";
  }
  out += "</svg>\n";
  return out;
}

}  // namespace gcode
