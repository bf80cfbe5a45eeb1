#include "gcode/report/layer_report.hpp"

#include <fmt/format.h>

#include <iterator>

#include "gcode/core/number.hpp"

namespace gcode {

namespace {

std::string features_text(const LayerRow& row, const LayerTracker& tracker) {
  std::string s;
  for (int id : row.features) {
    if (!s.empty()) s += ',';
    s += tracker.feature_name(id);
  }
  return s.empty() ? "-" : s;
}


void append_region(std::string& out, const LayerRow& r) {
  fmt::format_to(std::back_inserter(out), "\"first_line\": {}, \"last_line\": {}, \"byte_begin\": {}, \"byte_end\": {}",
                 r.first_line, r.last_line, r.byte_begin, r.byte_end);
}

// `time`: empty, or the time and cumulative columns of --time.
void table_row(std::string& out, const std::string& name, const std::string& slicer, const std::string& z,
               const std::string& h, const LayerRow& r, const std::string& features, const std::string& time = {}) {
  fmt::format_to(std::back_inserter(out), "{:>6} {:>6} {:>8} {:>6} {:>17} {:>23} {:>10.2f} {:>10.1f} {:>10.1f} {} {}\n", name,
                 slicer, z, h, r.first_line == 0 ? std::string("-") : fmt::format("{}-{}", r.first_line, r.last_line),
                 r.first_line == 0 ? std::string("-") : fmt::format("{}-{}", r.byte_begin, r.byte_end), r.filament,
                 r.path, r.travel, time, features);
}

std::string time_columns(double seconds, double cumulative) {
  return fmt::format("{:>9} {:>9}", format_duration(seconds), format_duration(cumulative));
}

}  // namespace

void append_json_string(std::string& out, std::string_view s) {
  out += '"';
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          fmt::format_to(std::back_inserter(out), "\\u{:04x}", static_cast<unsigned>(c));
        } else {
          out += c;
        }
    }
  }
  out += '"';
}

std::string layer_table_text(const LayerTable& table, const LayerTracker& tracker, const ReportOptions& o) {
  std::string out;
  const LayerTimes* t = o.times;
  fmt::format_to(std::back_inserter(out), "{:>6} {:>6} {:>8} {:>6} {:>17} {:>23} {:>10} {:>10} {:>10} {} {}\n", "layer",
                 "slicer", "z", "height", "lines", "bytes", "filament", "path", "travel",
                 t ? fmt::format("{:>9} {:>9}", "time", "cumul.") : std::string(), "features");
  double cumulative = t ? t->start : 0;
  table_row(out, "start", "-", "-", "-", table.start_code(), "-", t ? time_columns(t->start, t->start) : std::string());
  for (const LayerRow& r : table.layers()) {
    std::string time;
    if (t) {
      auto i = static_cast<std::size_t>(r.info.index - 1);
      double s = i < t->layers.size() ? t->layers[i] : 0;
      cumulative += s;
      time = time_columns(s, cumulative);
    }
    table_row(out, std::to_string(r.info.index), r.info.has_slicer_number ? std::to_string(r.info.slicer_number) : "-",
              fmt::format("{:.3f}", r.info.z), fmt::format("{:.3f}", r.info.height), r, features_text(r, tracker), time);
  }
  if (table.has_end_code())
    table_row(out, "end", "-", "-", "-", table.end_code(), "-", t ? time_columns(t->end, t->total()) : std::string());
  double grams = filament_mass_g(table.layers_extruded(), o.filament_diameter, o.density);
  fmt::format_to(std::back_inserter(out), "\n{} layers ({}), {} lines, {} bytes\n", table.layers().size(),
                 o.mode == LayerMode::Heuristic ? "found by Z, no layer markers"
                 : o.mode == LayerMode::Spiral  ? "turns of a spiral wall, no layer markers"
                                                : "from slicer markers",
                 table.total_lines(), table.total_bytes());
  fmt::format_to(std::back_inserter(out),
                 "filament: {:.1f} mm = {:.2f} m, {:.2f} g at {} g/cm3, {} mm (layers; whole file net {:.1f} mm)\n",
                 table.layers_extruded(), table.layers_extruded() / 1000, grams, o.density, o.filament_diameter,
                 table.total_filament());
  if (t) {
    fmt::format_to(std::back_inserter(out), "print time: {} (start code {}, layers {}, end code {})\n",
                   format_duration(t->total()), format_duration(t->start),
                   format_duration(t->total() - t->start - t->end), format_duration(t->end));
  }
  if (const FeatureTimes* f = o.features) {
    out += "time by feature (layers, at nominal speed; acceleration apart):";
    for (const FeatureTimes::Feature& x : f->features) fmt::format_to(std::back_inserter(out), " {} {:.1f} s,", x.name, x.seconds);
    if (f->unnamed > 0) fmt::format_to(std::back_inserter(out), " unnamed {:.1f} s,", f->unnamed);
    fmt::format_to(std::back_inserter(out),
                   " travel {:.1f} s, layer changes {:.1f} s, retraction {:.1f} s, acceleration {:.1f} s, waits {:.1f} s\n",
                   f->travel, f->layer_change, f->retract, f->acceleration, f->waits);
  }
  const Box3& b = table.extrusion_bounds();
  if (!b.empty()) {
    fmt::format_to(std::back_inserter(out), "extrusion bounds: X {:.3f}..{:.3f}  Y {:.3f}..{:.3f}  Z {:.3f}..{:.3f}\n",
                   b.min[0], b.max[0], b.min[1], b.max[1], b.min[2], b.max[2]);
  }
  return out;
}

std::string layer_table_json(const LayerTable& table, const LayerTracker& tracker, const ReportOptions& o) {
  std::string out = "{\n  \"schema\": \"gc-layers/1\",\n  \"file\": ";
  append_json_string(out, o.file_name);
  fmt::format_to(std::back_inserter(out), ",\n  \"layer_mode\": \"{}\",\n  \"start_code\": {{",
                 o.mode == LayerMode::Heuristic ? "heuristic" : o.mode == LayerMode::Spiral ? "spiral" : "markers");
  append_region(out, table.start_code());
  if (o.times) fmt::format_to(std::back_inserter(out), ", \"time_s\": {:.3f}", o.times->start);
  out += "},\n  \"end_code\": ";
  if (table.has_end_code()) {
    out += '{';
    append_region(out, table.end_code());
    if (o.times) fmt::format_to(std::back_inserter(out), ", \"time_s\": {:.3f}", o.times->end);
    out += '}';
  } else {
    out += "null";
  }
  out += ",\n  \"layers\": [";
  bool first = true;
  double cumulative = o.times ? o.times->start : 0;
  for (const LayerRow& r : table.layers()) {
    out += first ? "\n    {" : ",\n    {";
    first = false;
    char z[kMaxNumberChars], h[kMaxNumberChars];
    fmt::format_to(std::back_inserter(out), "\"layer\": {}, \"slicer_layer\": {}, \"z\": {}, \"height\": {}, ",
                   r.info.index, r.info.has_slicer_number ? std::to_string(r.info.slicer_number) : "null",
                   number_text(r.info.z, 6, z), number_text(r.info.height, 6, h));
    append_region(out, r);
    fmt::format_to(std::back_inserter(out),
                   ", \"filament_mm\": {:.5f}, \"extruded_mm\": {:.5f}, \"path_mm\": {:.3f}, \"travel_mm\": {:.3f}, "
                   "\"moves\": {}, \"empty\": {}, \"features\": [",
                   r.filament, r.extruded, r.path, r.travel, r.moves, r.info.empty ? "true" : "false");
    if (o.times) {
      auto i = static_cast<std::size_t>(r.info.index - 1);
      double s = i < o.times->layers.size() ? o.times->layers[i] : 0;
      cumulative += s;
      out.insert(out.size() - std::string_view(", \"features\": [").size(),
                 fmt::format(", \"time_s\": {:.3f}, \"cumulative_s\": {:.3f}", s, cumulative));
    }
    for (std::size_t i = 0; i < r.features.size(); ++i) {
      if (i) out += ", ";
      append_json_string(out, tracker.feature_name(r.features[i]));
    }
    out += "]}";
  }
  double grams = filament_mass_g(table.layers_extruded(), o.filament_diameter, o.density);
  fmt::format_to(std::back_inserter(out),
                 "\n  ],\n  \"summary\": {{\"layers\": {}, \"filament_mm\": {:.5f}, \"net_filament_mm\": {:.5f}, "
                 "\"filament_g\": {:.4f}, \"density_g_cm3\": {}, \"filament_diameter_mm\": {}, \"lines\": {}, "
                 "\"bytes\": {}, \"bounds\": ",
                 table.layers().size(), table.layers_extruded(), table.total_filament(), grams, o.density,
                 o.filament_diameter,
                 table.total_lines(), table.total_bytes());
  const Box3& b = table.extrusion_bounds();
  if (b.empty()) {
    out += "null";
  } else {
    fmt::format_to(std::back_inserter(out), "{{\"min\": [{:.4f}, {:.4f}, {:.4f}], \"max\": [{:.4f}, {:.4f}, {:.4f}]}}",
                   b.min[0], b.min[1], b.min[2], b.max[0], b.max[1], b.max[2]);
  }
  if (o.times)
    fmt::format_to(std::back_inserter(out), ", \"time_s\": {:.3f}, \"time\": \"{}\"", o.times->total(),
                   format_duration(o.times->total()));
  if (const FeatureTimes* f = o.features) {
    out += ", \"time_by_feature\": {\"features\": {";
    for (std::size_t i = 0; i < f->features.size(); ++i) {
      if (i) out += ", ";
      append_json_string(out, f->features[i].name);
      fmt::format_to(std::back_inserter(out), ": {:.3f}", f->features[i].seconds);
    }
    fmt::format_to(std::back_inserter(out),
                   "}}, \"unnamed_s\": {:.3f}, \"travel_s\": {:.3f}, \"layer_change_s\": {:.3f}, \"retract_s\": {:.3f}, "
                   "\"acceleration_s\": {:.3f}, \"waits_s\": {:.3f}, \"layers_s\": {:.3f}, \"start_code_s\": {:.3f}, "
                   "\"end_code_s\": {:.3f}}}",
                   f->unnamed, f->travel, f->layer_change, f->retract, f->acceleration, f->waits, f->layers(), f->start,
                   f->end);
  }
  out += "}\n}\n";
  return out;
}

}  // namespace gcode
