// Where a transform applies (pipeline/selection.hpp): --layers, --z-range and
// --types intersect, a range counted from the end needs the total, start and
// end code are selected only when no layer criterion is given, names match
// across slicers' spellings, errors name their option.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>
#include <vector>

#include "gcode/pipeline/pipeline.hpp"
#include "gcode/pipeline/selection.hpp"
#include "fn_stage.hpp"

using gcode::LayerSelection;
using gcode::SelectionText;

namespace {

// Five layers at Z 0.2 .. 1.0, each an outer wall then infill; start code
// before, end code after.
std::string five_layers() {
  std::string s = "G28\nG1 Z5 F600\n";
  for (int i = 0; i < 5; ++i) {
    char z[16];
    std::snprintf(z, sizeof z, "%.1f", 0.2 * (i + 1));
    s += ";LAYER:" + std::to_string(i) + "\nG1 Z" + z + "\n;TYPE:WALL-OUTER\nG1 X1 Y1 E1\n;TYPE:FILL\nG1 X2 Y2 E2\n";
  }
  return s + "G1 Z10\nM84\n";
}

SelectionText st(std::string layers, std::string z_range = "", std::string types = "") {
  return SelectionText{std::move(layers), std::move(z_range), std::move(types)};
}

// Per line: "<layer>:<text>" for every line the selection selects.
struct Picked {
  std::vector<std::string> lines;
  int layers_selected = 0;
  std::vector<std::string> unmatched;
};

Picked pick(const SelectionText& text, int total = 0) {
  struct Picker : gctest::SelectionStage {
    std::vector<std::string> lines;
    void line(const gcode::TrackedLine& t, gcode::Emitter& out) override {
      if (sel.selects(t)) lines.push_back(std::to_string(t.layer) + ":" + std::string(t.raw.text));
      out.pass(t);
    }
  } picker;
  picker.sel = LayerSelection::parse(text);
  if (total > 0) picker.sel.set_total(total);
  gcode::LayerMarkers markers;
  gcode::Pipeline pipeline(markers);
  picker.sel.bind(pipeline.tracker());
  pipeline.add(picker);
  pipeline.run_text(five_layers());
  return {picker.lines, picker.sel.layers_selected(), picker.sel.unmatched_types()};
}

std::vector<std::string> layer_lines(std::initializer_list<int> layers, bool wall = true, bool fill = true) {
  std::vector<std::string> out;
  for (int l : layers) {
    char z[16];
    std::snprintf(z, sizeof z, "%.1f", 0.2 * l);
    // A layer's first lines still carry the feature the last one ended with
    // (infill), the first layer's none.
    if ((wall && fill) || (fill && l > 1)) {
      out.push_back(std::to_string(l) + ":;LAYER:" + std::to_string(l - 1));
      out.push_back(std::to_string(l) + ":G1 Z" + z);
    }
    if (wall) {
      out.push_back(std::to_string(l) + ":;TYPE:WALL-OUTER");
      out.push_back(std::to_string(l) + ":G1 X1 Y1 E1");
    }
    if (fill) {
      out.push_back(std::to_string(l) + ":;TYPE:FILL");
      out.push_back(std::to_string(l) + ":G1 X2 Y2 E2");
    }
  }
  return out;
}

}  // namespace

TEST_CASE("selection: nothing given selects every line, start and end code too", "[selection]") {
  LayerSelection none = LayerSelection::parse({});
  CHECK_FALSE(none.any());
  CHECK_FALSE(none.by_layer());
  CHECK_FALSE(none.needs_total());
  Picked p = pick({});
  CHECK(p.lines.size() == 2 + 5 * 6 + 2);
  CHECK(p.lines.front() == "0:G28");
  CHECK(p.lines.back() == "5:M84");
  CHECK(p.layers_selected == 5);
}

TEST_CASE("selection: --layers keeps its layers, never start or end code", "[selection]") {
  Picked p = pick(st("2-3"));
  CHECK(p.lines == layer_lines({2, 3}));
  CHECK(p.layers_selected == 2);
  CHECK(pick(st("1,5")).lines == layer_lines({1, 5}));
  CHECK(pick(st("4-")).lines == layer_lines({4, 5}));
  CHECK(pick(st("9")).lines.empty());
}

TEST_CASE("selection: a range counted from the end needs the total", "[selection]") {
  auto sel = LayerSelection::parse(st("-2"));
  CHECK(sel.needs_total());
  CHECK(sel.by_layer());
  CHECK(pick(st("-2"), 5).lines == layer_lines({4, 5}));
  CHECK(pick(st("1,-1"), 5).lines == layer_lines({1, 5}));
  CHECK(pick(st("-2")).lines.empty());  // total unknown: nothing is the last two
  CHECK(pick(st("-9"), 5).lines == layer_lines({1, 2, 3, 4, 5}));
}

TEST_CASE("selection: --z-range by the layers' Z, edges included", "[selection]") {
  CHECK(pick(st("", "0.4:0.6")).lines == layer_lines({2, 3}));
  CHECK(pick(st("", "0.8:")).lines == layer_lines({4, 5}));
  CHECK(pick(st("", ":0.2")).lines == layer_lines({1}));
  CHECK(pick(st("", "0.65:0.75")).lines.empty());
}

TEST_CASE("selection: criteria intersect", "[selection]") {
  CHECK(pick(st("3-", ":0.8")).lines == layer_lines({3, 4}));
  CHECK(pick(st("1-2", "0.6:")).lines.empty());
  CHECK(pick(st("2,4", "", "FILL")).lines == layer_lines({2, 4}, false, true));
  CHECK(pick(st("-1", "0.2:1", "WALL-OUTER"), 5).lines == layer_lines({5}, true, false));
}

TEST_CASE("selection: --types by kind, any slicer's spelling", "[selection]") {
  Picked p = pick(st("", "", "External perimeter"));
  CHECK(p.lines == layer_lines({1, 2, 3, 4, 5}, true, false));
  CHECK(p.unmatched.empty());
  CHECK(p.layers_selected == 5);
  Picked q = pick(st("", "", "wall-outer, Ironing ,Sparse infill"));
  CHECK(q.unmatched == std::vector<std::string>{"Ironing"});
  // Start code has no feature yet, and the end code, though it carries the
  // last one (infill), is none: neither is selected by --types.
  std::vector<std::string> all = layer_lines({1, 2, 3, 4, 5});
  all.erase(all.begin(), all.begin() + 2);  // layer 1's first lines: no feature yet
  CHECK(q.lines == all);
}

TEST_CASE("selection: --types before any file is bound selects nothing", "[selection]") {
  auto sel = LayerSelection::parse(st("", "", "FILL"));
  CHECK(sel.any());
  CHECK_FALSE(sel.by_layer());
  CHECK_FALSE(sel.feature_selected(0));
  CHECK_FALSE(sel.feature_selected(-1));
  CHECK(sel.unmatched_types() == std::vector<std::string>{"FILL"});
  CHECK(LayerSelection::parse({}).feature_selected(-1));
}

TEST_CASE("selection: a parse error names its option", "[selection]") {
  auto message = [](const SelectionText& t) {
    try {
      LayerSelection::parse(t);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(message(st("3-1")) == "--layers: bad layer range '3-1': 3-1 runs backwards");
  CHECK(message(st("0")).rfind("--layers: bad layer range '0'", 0) == 0);
  CHECK(message(st("", "2")) == "--z-range: bad Z range '2': expected Z1:Z2");
  CHECK(message(st("", "2:1")) == "--z-range: bad Z range '2:1': runs backwards");
  CHECK(message(st("", "", ", ,")) == "--types: give ;TYPE: names, e.g. WALL-OUTER");
}

TEST_CASE("selection: split_list trims and skips empty items", "[selection]") {
  using V = std::vector<std::string>;
  CHECK(gcode::split_list(" a , b,,c ") == V{"a", "b", "c"});
  CHECK(gcode::split_list("External perimeter,FILL") == V{"External perimeter", "FILL"});
  CHECK(gcode::split_list("").empty());
  CHECK(gcode::split_list(",").empty());
  CHECK(gcode::split_list("one") == V{"one"});
}
