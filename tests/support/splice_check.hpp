#pragma once
// The independent checker of spliced output (gc-swap-layer, gc-relayer).
//
// The test says what the output must be made of: pieces of source files
// (line ranges, found with the library's layer tracker), each with the Z
// shift and extrusion factor the rules call for. The checker replays the
// output and every source through MachineState and walks the output:
//
//   - each piece must appear in order, every move identical to its source
//     apart from the shift (same X, Y, F; Z = source Z + shift; the same
//     filament, times the factor for extruding moves), every other line
//     byte for byte (a G92 with its Z shifted);
//   - what lies between two pieces is a seam: its moves push exactly the
//     retraction in effect before it minus the one the next piece starts
//     with (retract + unretract), never go below what is printed, travel in
//     XY above it; after it the output stands as the next piece expects
//     (modes, F, tool, XY, the E coordinate, temperatures and fan);
//   - nothing comes after the last piece.
//
// It knows nothing of how the tools build seams: only the printer's view.
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/fixed.hpp"
#include "gcode/core/layer_marker.hpp"
#include "gcode/core/layer_tracker.hpp"
#include "gcode/core/line.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/transform/pause_sequence.hpp"
#include "test_support.hpp"

namespace gctest {

struct Replayed {
  std::string text;  // without its ending
  gcode::Line line;  // views into `text`: valid while the vector is not resized
  gcode::Move move;
  gcode::MachineState before, after;
  double retracted_before = 0;  // E retraction in effect before the line
  double top_before = 0;        // highest Z extruded at before the line
};

inline bool is_motion(const gcode::Move& m) {
  return m.kind == gcode::MoveKind::Linear || m.kind == gcode::MoveKind::Arc;
}

inline std::vector<Replayed> replay_lines(std::string_view text) {
  std::vector<Replayed> lines;
  gcode::MemoryLineSplitter split(text);
  gcode::RawLine raw;
  while (split.next(raw)) lines.emplace_back().text.assign(raw.text);
  gcode::MachineState state;
  gcode::RetractionTracker retraction;
  double top = 0;
  for (Replayed& r : lines) {
    r.line = gcode::Line::parse(r.text);
    r.before = state;
    r.retracted_before = retraction.pending();
    r.top_before = top;
    r.move = state.apply(r.line);
    r.after = state;
    retraction.observe(r.move);
    if (r.move.extruding) top = std::max(top, r.move.end[gcode::kZ]);
  }
  return lines;
}

// Where each layer starts (0-based line), as the library's tracker sees it.
struct LayerLines {
  std::vector<std::size_t> first;  // first[k - 1]: layer k
  std::vector<double> z, height;
  std::size_t end_code = 0;  // the end code's first line (== lines when empty)
  std::size_t lines = 0;

  std::size_t start(int layer) const { return layer > static_cast<int>(first.size()) ? end_code : first[static_cast<std::size_t>(layer - 1)]; }
  int count() const { return static_cast<int>(first.size()); }
};

inline LayerLines layer_lines(std::string_view text) {
  struct Sink : gcode::LayerSink {
    LayerLines l;
    bool end = false;
    void on_layer(const gcode::LayerInfo& info, const gcode::MachineState&) override {
      l.first.push_back(info.first_line - 1);
      l.z.push_back(info.z);
      l.height.push_back(info.height);
    }
    void on_end_code(std::uint64_t first_line, std::uint64_t, const gcode::MachineState&) override {
      end = true;
      l.end_code = first_line == 0 ? static_cast<std::size_t>(-1) : first_line - 1;
    }
    void on_line(const gcode::TrackedLine&) override { ++l.lines; }
  } sink;
  gcode::LayerMarkers markers;
  gcode::LayerTracker tracker(sink, markers);
  gcode::MemoryLineSplitter split(text);
  gcode::RawLine raw;
  while (split.next(raw)) tracker.push(raw);
  tracker.finish();
  if (!sink.end || sink.l.end_code == static_cast<std::size_t>(-1)) sink.l.end_code = sink.l.lines;
  return sink.l;
}

struct SpliceSegment {
  std::string name;
  const std::vector<Replayed>* source = nullptr;
  std::size_t first = 0, last = 0;  // source lines [first, last)
  double z_shift = 0;
  double scale = 1;
  bool e_converted = false;  // written in the other E mode
  double seam_extra = 0;     // filament the seam before it pushes beyond its retraction (a purge)
};

// A file of tests/fixtures/pairs, read, replayed and split into layers once.
struct PairFile {
  std::string path;
  std::string text;
  std::vector<Replayed> lines;
  LayerLines layers;
  double top = 0;  // the highest Z extruded at

  double z(int layer) const { return layers.z[static_cast<std::size_t>(layer - 1)]; }
  double height(int layer) const { return layers.height[static_cast<std::size_t>(layer - 1)]; }
  // The first layer above `z` (0: none).
  int first_above(double at) const {
    for (int k = 1; k <= layers.count(); ++k)
      if (z(k) > at + 1e-6) return k;
    return 0;
  }
};

inline const PairFile& pair_file(const std::string& name) {
  static std::map<std::string, std::unique_ptr<PairFile>> cache;
  auto& f = cache[name];
  if (!f) {
    f = std::make_unique<PairFile>();
    f->path = fixture_path("pairs/" + name);
    f->text = read_file(f->path);
    f->lines = replay_lines(f->text);
    f->layers = layer_lines(f->text);
    for (const Replayed& l : f->lines)
      if (l.move.extruding) f->top = std::max(f->top, l.move.end[gcode::kZ]);
  }
  return *f;
}

// Past the last layer: a part to the end of its file, end code included.
inline constexpr int kToEnd = 1 << 20;

// Layers [first, end) of a pair file (first 0: from its first line; end one past
// the last layer: up to the end code).
inline SpliceSegment pair_part(const std::string& name, int first, int end, double shift = 0, double scale = 1) {
  const PairFile& f = pair_file(name);
  SpliceSegment s;
  s.name = name + " layers " + std::to_string(first) + "-" + std::to_string(end - 1);
  s.source = &f.lines;
  s.first = first == 0 ? 0 : f.layers.start(first);
  s.last = end > f.layers.count() + 1 ? f.lines.size() : f.layers.start(end);
  s.z_shift = shift;
  s.scale = scale;
  return s;
}

struct SeamReport {
  std::size_t first = 0, last = 0;  // output lines [first, last)
  double net_filament = 0;
  double expected_net = 0;
  double top_before = 0;
  double lowest_z = 1e300;   // of its head moves
  double travel_z = 1e300;   // of its XY moves
  gcode::MachineState after;
  std::vector<std::string> lines;
};

struct SpliceCheck {
  std::vector<std::string> failures;
  std::vector<SeamReport> seams;
  double top_z = 0;  // the highest Z extruded at in the output

  std::string first_failure() const { return failures.empty() ? std::string() : failures.front(); }
  void fail(std::string message) {
    if (failures.size() < 20) failures.push_back(std::move(message));
  }
};

namespace detail {

inline gcode::Fixed fx(double v) { return gcode::Fixed::from_double(v).rounded(6); }

// Whether an output line is its source line moved by the segment's rules.
inline std::string mismatch(const Replayed& out, const Replayed& src, const SpliceSegment& s) {
  const bool plain = s.z_shift == 0 && s.scale == 1 && !s.e_converted;
  if (plain) return out.text == src.text ? std::string() : "text differs";
  if (is_motion(src.move)) {
    if (!is_motion(out.move) || out.line.number != src.line.number) return "not the same move";
    using gcode::kX, gcode::kY, gcode::kZ, gcode::kE;
    if (out.after.at(kX) != src.after.at(kX) || out.after.at(kY) != src.after.at(kY)) return "XY differs";
    if (fx(out.after.position[kZ]) != fx(src.after.position[kZ] + s.z_shift)) return "Z is not the source's plus the shift";
    if (out.after.feedrate != src.after.feedrate) return "F differs";
    double want = src.move.extruding ? src.move.filament * s.scale : src.move.filament;
    double tolerance = src.move.extruding && s.scale != 1 ? 2e-5 : 1e-9;
    if (std::fabs(out.move.filament - want) > tolerance) return "filament differs";
    return {};
  }
  if (out.text == src.text) return {};
  if (src.line.is_g(92) && out.line.is_g(92)) {
    const gcode::Word* sz = src.line.find('Z');
    const gcode::Word* oz = out.line.find('Z');
    if ((sz == nullptr) != (oz == nullptr)) return "G92 Z differs";
    if (sz != nullptr && fx(oz->value()) != fx(sz->value() + s.z_shift)) return "G92 Z is not shifted";
    const gcode::Word* se = src.line.find('E');
    const gcode::Word* oe = out.line.find('E');
    if ((se == nullptr) != (oe == nullptr) || (se != nullptr && se->fixed() != oe->fixed())) return "G92 E differs";
    return {};
  }
  return "text differs";
}

inline bool starts_here(const std::vector<Replayed>& out, std::size_t at, const SpliceSegment& s) {
  std::size_t n = std::min<std::size_t>(3, s.last - s.first);
  if (at + n > out.size()) return false;
  for (std::size_t k = 0; k < n; ++k)
    if (!mismatch(out[at + k], (*s.source)[s.first + k], s).empty()) return false;
  return true;
}

}  // namespace detail

inline SpliceCheck check_splice(std::string_view output, const std::vector<SpliceSegment>& segments) {
  using gcode::kX, gcode::kY, gcode::kZ, gcode::kE;
  SpliceCheck c;
  std::vector<Replayed> out = replay_lines(output);
  std::size_t pos = 0;
  for (std::size_t si = 0; si < segments.size(); ++si) {
    const SpliceSegment& s = segments[si];
    const std::vector<Replayed>& src = *s.source;
    if (s.first >= s.last || s.last > src.size()) {
      c.fail(s.name + ": empty or bad line range");
      continue;
    }
    std::size_t start = pos;
    while (start < out.size() && !detail::starts_here(out, start, s)) ++start;
    if (start >= out.size()) {
      c.fail(s.name + ": not found in the output after line " + std::to_string(pos + 1));
      return c;
    }
    if (start > pos || si > 0) {
      SeamReport seam;
      seam.first = pos;
      seam.last = start;
      seam.top_before = pos < out.size() ? out[pos].top_before : 0;
      const Replayed& next = src[s.first];
      seam.expected_net = (pos < out.size() ? out[pos].retracted_before : 0) - next.retracted_before + s.seam_extra;
      for (std::size_t i = pos; i < start; ++i) {
        const Replayed& r = out[i];
        seam.lines.push_back(r.text);
        if (!is_motion(r.move)) continue;
        seam.net_filament += r.move.filament;
        if (r.move.moves_head()) seam.lowest_z = std::min(seam.lowest_z, r.move.end[kZ]);
        if (r.move.xy_length > 0) seam.travel_z = std::min({seam.travel_z, r.move.start[kZ], r.move.end[kZ]});
        if (r.move.extruding) c.fail("seam before " + s.name + ": extrudes at output line " + std::to_string(i + 1));
      }
      seam.after = out[start].before;
      const std::string where = "seam before " + s.name + " (output lines " + std::to_string(pos + 1) + "-" +
                                std::to_string(start) + ")";
      if (std::fabs(seam.net_filament - seam.expected_net) > 1e-9)
        c.fail(where + ": its moves push " + std::to_string(seam.net_filament) + " mm, not the " +
               std::to_string(seam.expected_net) + " mm of retraction it must make up");
      if (seam.lowest_z < seam.top_before - 1e-9 && seam.lowest_z != 1e300)
        c.fail(where + ": goes down to Z " + std::to_string(seam.lowest_z) + " below the printed " +
               std::to_string(seam.top_before));
      if (seam.travel_z != 1e300 && seam.travel_z <= seam.top_before + 1e-6)
        c.fail(where + ": travels in XY at Z " + std::to_string(seam.travel_z) + ", not above the printed " +
               std::to_string(seam.top_before));
      const gcode::MachineState& a = seam.after;
      const gcode::MachineState& b = next.before;
      if (a.relative_xyz != b.relative_xyz) c.fail(where + ": positioning mode differs after it");
      if (!s.e_converted && a.relative_e != b.relative_e) c.fail(where + ": E mode differs after it");
      if (s.e_converted && a.relative_e == b.relative_e) c.fail(where + ": E mode expected to stay the output's");
      if (b.feedrate > 0 && a.feedrate != b.feedrate) c.fail(where + ": F differs after it");
      if (a.tool != b.tool) c.fail(where + ": tool differs after it");
      if (b.known[kX] && (a.at(kX) != b.at(kX) || a.at(kY) != b.at(kY))) c.fail(where + ": XY differs after it");
      if (!s.e_converted && a.at(kE) != b.at(kE)) c.fail(where + ": the E coordinate differs after it");
      for (std::size_t t = 0; t < b.hotend_target.size(); ++t)
        if (b.hotend_target[t] > 0 && a.hotend_target[t] != b.hotend_target[t])
          c.fail(where + ": hotend temperature differs after it");
      if (b.bed_target > 0 && a.bed_target != b.bed_target) c.fail(where + ": bed temperature differs after it");
      // The fan only where the source set it before (else it is left as it was).
      bool fan_set = false;
      for (std::size_t i = 0; i < s.first && !fan_set; ++i) fan_set = src[i].line.is_m(106) || src[i].line.is_m(107);
      if (fan_set && a.fan != b.fan) c.fail(where + ": fan differs after it");
      c.seams.push_back(std::move(seam));
    }
    for (std::size_t j = s.first; j < s.last; ++j) {
      std::size_t o = start + (j - s.first);
      if (o >= out.size()) {
        c.fail(s.name + ": output ends at its source line " + std::to_string(j + 1));
        return c;
      }
      std::string why = detail::mismatch(out[o], src[j], s);
      if (!why.empty())
        c.fail(s.name + ": output line " + std::to_string(o + 1) + " '" + out[o].text + "' is not source line " +
               std::to_string(j + 1) + " '" + src[j].text + "': " + why);
    }
    pos = start + (s.last - s.first);
  }
  if (pos < out.size()) c.fail("the output goes on after the last piece, at line " + std::to_string(pos + 1));
  for (const Replayed& r : out)
    if (r.move.extruding) c.top_z = std::max(c.top_z, r.move.end[kZ]);
  return c;
}

}  // namespace gctest
