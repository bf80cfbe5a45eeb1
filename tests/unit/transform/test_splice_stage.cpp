// The splice (transform/splice.hpp): SpliceRewrite's Z and E arithmetic,
// BlockStream's pull-style pacing, and SpliceStage with small plans: nothing
// planned changes nothing; blocks come with their layer events; CRLF stays.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "gcode/core/layer_marker.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "gcode/transform/layer_index.hpp"
#include "gcode/transform/splice.hpp"
#include "splice_check.hpp"
#include "test_support.hpp"

namespace {

// Applies a SpliceRewrite to every line but the first, which sets the
// source's modes (as a block's prelude does).
struct RewriteStage : gcode::Stage {
  explicit RewriteStage(const gcode::Precision& p) : precision(p) {}
  void line(const gcode::TrackedLine& t, gcode::Emitter& out) override {
    std::string_view text;
    if (t.raw.number > 1 && rewrite.apply(t, precision, text)) {
      out.replace(t, text);
    } else {
      out.pass(t);
    }
  }
  gcode::SpliceRewrite rewrite;
  const gcode::Precision& precision;
};

std::string rewritten(const std::string& text, gcode::Fixed shift, double scale, bool relative_e, gcode::Fixed e) {
  gcode::LayerMarkers markers;
  gcode::Pipeline pipeline(markers, gcode::PipelineOptions{.layers = false});
  RewriteStage stage(pipeline.precision());
  stage.rewrite.reset(shift, scale, relative_e, e);
  pipeline.add(stage);
  return gctest::run_stages(pipeline, text);
}

gcode::Fixed fixed_of(std::int64_t mantissa, int decimals) { return gcode::Fixed::from_decimal(mantissa, decimals); }


// A plan from a table: per main layer, keep or not and the blocks first.
struct TablePlan : gcode::SplicePlan {
  std::function<gcode::LayerAction(const gcode::LayerInfo&, const gcode::SpliceContext&)> at;
  gcode::LayerAction at_layer(const gcode::LayerInfo& info, const gcode::SpliceContext& c) override {
    if (at) return at(info, c);
    gcode::LayerAction a;
    a.shift = c.shift;
    return a;
  }
  gcode::LayerAction at_end_code(const gcode::SpliceContext& c) override {
    gcode::LayerAction a;
    a.shift = c.shift;
    return a;
  }
};

struct Collect : gcode::SpliceSink {
  std::vector<std::string> lines;
  std::vector<double> layer_z;
  void line(std::string_view text) override { lines.emplace_back(text); }
  void layer(const gcode::LayerInfo& info, const gcode::MachineState&) override { layer_z.push_back(info.z); }
  void end_code(const gcode::EndCodeInfo&, const gcode::MachineState&) override {}
};

}  // namespace

TEST_CASE("splice rewrite: absolute Z is shifted exactly, relative Z is not", "[splice][rewrite]") {
  CHECK(rewritten("G90\nG1 Z0.3\n", gcode::Fixed::from_decimal(-1, 1), 1, false, {}) == "G90\nG1 Z0.2\n");
  std::string in = "G90\nG1 Z1.25 X1 ; lift\nG0 Z.4\nG92 Z2\nG91\nG1 Z0.5\nG90\nG1 X2\n";
  CHECK(rewritten(in, fixed_of(2, 1), 1, false, {}) ==
        "G90\nG1 Z1.45 X1 ; lift\nG0 Z0.6\nG92 Z2.2\nG91\nG1 Z0.5\nG90\nG1 X2\n");
  // Shifts keep the input's decimals: no binary noise.
  CHECK(rewritten("G90\nG1 Z0.1\n", fixed_of(2, 1), 1, false, {}) == "G90\nG1 Z0.3\n");
}

TEST_CASE("splice rewrite: E into the other mode, the coordinate carried", "[splice][rewrite]") {
  // An absolute source written as relative amounts.
  CHECK(rewritten("M82\nG1 X1 E1.5\nG1 X2 E2.25\nG1 E1.25\n", {}, 1, true, {}) ==
        "M82\nG1 X1 E1.5\nG1 X2 E0.75\nG1 E-1\n");
  // A mode line of the source's own switches the output to it.
  CHECK(rewritten("M82\nG1 X1 E1\nM83\nG1 X2 E0.5\n", {}, 1, true, {}) == "M82\nG1 X1 E1\nM83\nG1 X2 E0.5\n");
  // A relative source written as coordinates from 10.
  CHECK(rewritten("M83\nG1 X1 E0.5\nG1 X2 E.25\nG1 E-0.8\n", {}, 1, false, fixed_of(10, 0)) ==
        "M83\nG1 X1 E10.5\nG1 X2 E10.75\nG1 E9.95\n");
}

TEST_CASE("splice rewrite: extrusion scaled with the rounding carried, retractions left alone", "[splice][rewrite]") {
  std::string out = rewritten("M83\nG1 X1 E0.00003\nG1 X2 E0.00003\nG1 X3 E0.00003\nG1 E-0.8\nG1 E0.8\n", {}, 0.5,
                              true, {});
  CHECK(out == "M83\nG1 X1 E0.00002\nG1 X2 E0.00001\nG1 X3 E0.00002\nG1 E-0.8\nG1 E0.8\n");
  // Absolute E: coordinates of the scaled amounts.
  CHECK(rewritten("M82\nG1 X1 E2\nG1 X2 E4\n", {}, 1.5, false, {}) == "M82\nG1 X1 E3\nG1 X2 E6\n");
}

TEST_CASE("splice block stream: pull style, a bounded piece per pump", "[splice][block]") {
  std::string path = gctest::fixture_path("pairs/cura_block_0.1_infill20.gcode");
  gctest::OpenedFile f(path);
  gcode::LayerMarkers markers;
  gcode::LayerIndex index(f.fd(), "block", markers);
  index.read_all();
  gcode::SpliceBlock b = gcode::layer_index_block(index, 5, index.layers(), true);
  gcode::StreamPoint printed = index.point(5);  // the printer stands where the block starts
  printed.top_z = index.layer(4).info.z;
  gcode::Precision precision;
  gcode::BlockStream stream(b, printed, gcode::SeamOptions{}, precision);
  Collect sink;
  std::size_t pumps = 0, most = 0;
  for (std::size_t before = 0; stream.pump(sink); before = sink.lines.size()) {
    ++pumps;
    most = std::max(most, sink.lines.size() - before);
  }
  // The rest of the file, 70 kB, in several pieces of at most one read's lines.
  CHECK(pumps > 1);
  CHECK(most < 3000);
  CHECK(sink.layer_z.size() == static_cast<std::size_t>(index.layers() - 4));
  // After the seam, the block's lines as they are (same file, no shift).
  std::vector<std::string> src = gctest::split_lines(gctest::read_file(path));
  std::size_t first = static_cast<std::size_t>(index.layer(5).info.first_line - 1);
  std::size_t seam = sink.lines.size() - (src.size() - first);
  for (std::size_t i = first; i < src.size(); ++i) {
    std::string l = src[i];
    while (!l.empty() && (l.back() == '\n' || l.back() == '\r')) l.pop_back();
    REQUIRE(sink.lines[seam + i - first] == l);
  }
  CHECK(printed.top_z == Approx(index.layer(index.layers()).info.z));
}

TEST_CASE("splice stage: a plan that changes nothing gives the input byte for byte", "[splice][stage]") {
  for (const std::string& name : gctest::fixture_names()) {
    INFO(name);
    std::string text = gctest::read_file(gctest::fixture_path(name));
    TablePlan plan;
    gcode::LayerMarkers markers;
    gcode::Pipeline pipeline(markers);
    gcode::SpliceStage stage(plan, pipeline.precision(), gcode::SeamOptions{});
    pipeline.add(stage);
    CHECK(gctest::run_stages(pipeline, text) == text);
    CHECK(stage.seams() == 0);
  }
}

TEST_CASE("splice stage: a layer left out and printed again from the input itself", "[splice][stage]") {
  std::string path = gctest::fixture_path("pairs/prusa_block_0.2_infill20.gcode");
  std::string text = gctest::read_file(path);
  gctest::OpenedFile f(path);
  gcode::LayerMarkers markers;
  TablePlan plan;
  // Layer 3 left out; at layer 6, layer 5 printed once more in its place 0.2 up.
  plan.at = [&](const gcode::LayerInfo& info, const gcode::SpliceContext& c) {
    gcode::LayerAction a;
    a.shift = c.shift;
    if (info.index == 3) {
      a.keep = false;
      a.shift -= fixed_of(2, 1);
    }
    if (info.index == 6) {
      const gcode::PassedLayer& p = *c.previous;
      gcode::SpliceBlock b;
      b.fd = f.fd();
      b.name = "self";
      b.markers = &markers;
      b.begin = p.info.offset;
      b.end = p.end;
      b.first_layer = p.info;
      b.start = p.start;
      b.z_shift = c.shift + fixed_of(2, 1);
      a.shift = b.z_shift;
      a.blocks.push_back(b);
    }
    return a;
  };
  gcode::Pipeline pipeline(markers);
  gcode::SpliceStage stage(plan, pipeline.precision(), gcode::SeamOptions{});
  pipeline.add(stage);
  std::string out = gctest::run_stages(pipeline, text);
  CHECK(stage.layers_left_out() == 1);
  CHECK(stage.blocks() == 1);
  std::vector<gctest::Replayed> src = gctest::replay_lines(text);
  gctest::LayerLines layers = gctest::layer_lines(text);
  auto seg = [&](int first, int end, double shift) {
    gctest::SpliceSegment s;
    s.name = "layers " + std::to_string(first) + "-" + std::to_string(end - 1);
    s.source = &src;
    s.first = first == 0 ? 0 : layers.start(first);
    s.last = end > layers.count() ? src.size() : layers.start(end);
    s.z_shift = shift;
    return s;
  };
  gctest::SpliceCheck c = gctest::check_splice(out, {seg(0, 3, 0), seg(4, 6, -0.2), seg(5, 6, 0), seg(6, 1000, 0)});
  INFO(c.first_failure());
  CHECK(c.failures.empty());
  CHECK(c.seams.size() == 3);
}

TEST_CASE("splice stage: lines it writes get the input's CRLF", "[splice][stage]") {
  std::string text = gctest::read_file(gctest::fixture_path("pairs/cura_block_0.2_infill20.gcode"));
  std::string crlf;
  for (char ch : text) crlf += ch == '\n' ? std::string("\r\n") : std::string(1, ch);
  TablePlan plan;
  plan.at = [](const gcode::LayerInfo& info, const gcode::SpliceContext& c) {
    gcode::LayerAction a;
    a.shift = c.shift;
    a.keep = info.index != 4;
    return a;
  };
  gcode::LayerMarkers markers;
  gcode::Pipeline pipeline(markers);
  gcode::SpliceStage stage(plan, pipeline.precision(), gcode::SeamOptions{});
  pipeline.add(stage);
  std::string out = gctest::run_stages(pipeline, crlf);
  CHECK(stage.seams() == 1);
  for (const std::string& l : gctest::split_lines(out)) REQUIRE(l.substr(l.size() - 2) == "\r\n");
}

TEST_CASE("splice printers: another bed is said, a part elsewhere is refused", "[splice][stage]") {
  gcode::PrintArea input, other;
  input.has_bed = other.has_bed = true;
  input.bed = other.bed = gcode::Box2{0, 0, 220, 220};
  CHECK(gcode::printer_difference(input, other, "b.gcode").empty());
  other.bed = gcode::Box2{0, 0, 250, 210};
  CHECK(gcode::printer_difference(input, other, "b.gcode") ==
        "b.gcode was sliced for a 250x210 mm bed, the input for 220x220 mm: its moves are used as they are");
  other.has_bed = false;  // nothing known: nothing said
  CHECK(gcode::printer_difference(input, other, "b.gcode").empty());

  const gcode::Box2 printed{94, 94, 126, 126};
  CHECK(gcode::placement_difference(printed, gcode::Box2{95, 95, 127, 127}, "b.gcode").empty());  // 1.4 mm
  CHECK(gcode::placement_difference(printed, gcode::Box2{109, 84, 141, 116}, "b.gcode").find(
            "b.gcode does not lie where the input prints: its part is centred at X125 Y100, the input's at X110 "
            "Y110 (18 mm apart)") == 0);
  CHECK(gcode::placement_difference(gcode::Box2{}, printed, "b.gcode").empty());
}
