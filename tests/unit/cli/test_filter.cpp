// One run of a filter (cli/filter.hpp): input to output through the tool's
// stages; -i atomic (FILE replaced only when the run and its checks
// succeed); a pipe spooled when the layers must be counted or scanned
// first, the output still the whole input; the E mode guessed once with one
// warning; stop_when reads no further; the printer's bed from either end.
#include <catch2/catch.hpp>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "gcode/cli/filter.hpp"
#include "capture.hpp"
#include "fn_stage.hpp"

using gcode::cli::Filter;
using gcode::cli::FilterOptions;

namespace {

std::string layers(int n, bool relative_e_without_m83 = false) {
  std::string s = relative_e_without_m83 ? "G28\n" : "M82\nG28\n";
  for (int i = 0; i < n; ++i) {
    s += ";LAYER:" + std::to_string(i) + "\n;TYPE:" + (i % 2 ? "FILL" : "WALL-OUTER") + "\nG1 Z" +
         std::to_string(0.2 * (i + 1)).substr(0, 3) + "\n";
    for (int k = 0; k < 6; ++k)
      s += "G1 X" + std::to_string(k * 10 + i) + " Y" + std::to_string(k % 2 * 10) + " E" +
           (relative_e_without_m83 ? std::string(k % 2 ? "0.4" : "0.7") : std::to_string(i * 6 + k + 1)) + "\n";
  }
  return s + "M84\n";
}

struct Dir {
  std::string path = gctest::temp_dir();
  std::string file(const std::string& name, const std::string& text) const {
    std::string p = path + "/" + name;
    gctest::write_file(p, text);
    return p;
  }
  std::size_t entries() const {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(path)) ++n;
    return n;
  }
};

// Adds " ; L<layer>" to every line of the selected layers.
struct Tagger : gctest::SelectionStage {
  void line(const gcode::TrackedLine& t, gcode::Emitter& out) override {
    if (sel.selects(t)) return out.replace(t, std::string(t.raw.text) + " ; L" + std::to_string(t.layer));
    out.pass(t);
  }
};

}  // namespace

TEST_CASE("filter: FILE to -o through the stages", "[filter]") {
  Dir d;
  FilterOptions o;
  o.file = d.file("in.gcode", layers(3));
  o.output = d.path + "/out.gcode";
  Filter run(o);
  gctest::FnStage upper([](const gcode::TrackedLine& t, gcode::Emitter& out) {
    if (t.raw.text == "M84") return out.replace(t, "M84 ; motors off");
    out.pass(t);
  });
  run.add(upper);
  run.write();
  std::string expected = layers(3);
  expected.replace(expected.find("M84"), 3, "M84 ; motors off");
  CHECK(gctest::read_file(o.output) == expected);
  REQUIRE(run.output() != nullptr);
  CHECK(run.output()->bytes_written() == expected.size());
}

TEST_CASE("filter: -i replaces FILE only when everything succeeded", "[filter]") {
  Dir d;
  const std::string original = layers(3);
  FilterOptions o;
  o.file = d.file("print.gcode", original);
  o.in_place = true;
  SECTION("a stage fails mid-stream") {
    Filter run(o);
    gctest::FnStage failing([](const gcode::TrackedLine& t, gcode::Emitter& out) {
      if (t.layer == 2) throw gcode::cli::InputError("layer 2 cannot be done");
      out.replace(t, "; gone");
    });
    run.add(failing);
    CHECK_THROWS_AS(run.write(), gcode::cli::InputError);
  }
  SECTION("the check after the run fails") {
    Filter run(o);
    gctest::FnStage blank([](const gcode::TrackedLine& t, gcode::Emitter& out) { out.replace(t, "; gone"); });
    run.add(blank);
    CHECK_THROWS_AS(run.write([] { throw gcode::cli::InputError("no such layer"); }), gcode::cli::InputError);
  }
  CHECK(gctest::read_file(o.file) == original);
  CHECK(d.entries() == 1);  // no temp file left beside it
  Filter ok(o);
  gctest::FnStage blank([](const gcode::TrackedLine& t, gcode::Emitter& out) {
    if (t.raw.text == "G28") return out.replace(t, "G28 X Y");
    out.pass(t);
  });
  ok.add(blank);
  ok.write();
  std::string expected = original;
  expected.replace(expected.find("G28"), 3, "G28 X Y");
  CHECK(gctest::read_file(o.file) == expected);
  CHECK(d.entries() == 1);
}

TEST_CASE("filter: a range from the end counts a pipe's layers, then writes all of it", "[filter]") {
  Dir d;
  FilterOptions o;
  o.output = d.path + "/out.gcode";
  const std::string text = layers(4);
  gctest::with_piped_stdin(text, [&] {
    Filter run(o);
    Tagger tagger;
    tagger.sel = run.selection(gcode::SelectionText{"-2", "", ""});
    run.add(tagger);
    run.write();
    CHECK(tagger.sel.layers_selected() == 2);
  });
  std::string out = gctest::read_file(o.output);
  CHECK(out.find(" ; L1") == std::string::npos);
  CHECK(out.find(" ; L2") == std::string::npos);
  CHECK(out.find(";LAYER:2 ; L3\n") != std::string::npos);
  CHECK(out.find("G1 X53 Y10 E24 ; L4\nM84\n") != std::string::npos);
  CHECK(out.substr(0, 11) == "M82\nG28\n;LA");
}

TEST_CASE("filter: scan lists the layers and features, then the run starts again", "[filter]") {
  Dir d;
  FilterOptions o;
  o.output = d.path + "/out.gcode";
  const std::string text = layers(3);
  gctest::with_piped_stdin(text, [&] {
    Filter run(o);
    gcode::cli::InputScan scan = run.scan();
    REQUIRE(scan.layers.size() == 3);
    CHECK(scan.layers[0].index == 1);
    CHECK(scan.layers[2].index == 3);
    CHECK(scan.layers[2].z == Approx(0.6));
    CHECK(scan.features == std::vector<std::string>{"WALL-OUTER", "FILL"});
    CHECK(run.count_layers() == 3);
    run.write();
  });
  CHECK(gctest::read_file(o.output) == text);
  CHECK(gcode::cli::count_layers(gctest::OpenedFile(d.path + "/out.gcode").fd(), gcode::LayerMarkers()) == 3);
}

TEST_CASE("filter: the E mode of a file that never sets it, with one warning", "[filter]") {
  Dir d;
  const std::string path = d.file("rel.gcode", layers(3, true));
  auto relative_read = [&](const std::string& mode, bool quiet, std::string* err) {
    FilterOptions o;
    o.file = path;
    o.e_mode = mode;
    o.quiet = quiet;
    o.tool = "gc-test";
    bool relative = false, state_relative = false;
    *err = gctest::stderr_of([&] {
      Filter run(o);
      relative = run.e_mode();
      CHECK(run.e_mode() == relative);  // decided once
      run.run();
      state_relative = run.pipeline().tracker().state().relative_e;
    });
    CHECK(state_relative == relative);
    return relative;
  };
  std::string err;
  CHECK(relative_read("auto", false, &err));
  CHECK(err.rfind("gc-test: warning: " + path + " never sets the E mode (M82/M83); reading its E values as relative: ", 0) == 0);
  CHECK(err.find("(--e-mode relative|absolute to say)\n") != std::string::npos);
  CHECK(std::count(err.begin(), err.end(), '\n') == 1);
  CHECK(relative_read("auto", true, &err));
  CHECK(err.empty());
  CHECK_FALSE(relative_read("absolute", false, &err));
  CHECK(err.empty());
  CHECK(relative_read("relative", false, &err));
  CHECK(err.empty());
  // A file that says M82 itself: nothing guessed, nothing said.
  FilterOptions o;
  o.file = d.file("abs.gcode", layers(3));
  o.e_mode = "relative";
  err = gctest::stderr_of([&] {
    Filter run(o);
    CHECK_FALSE(run.e_mode());
  });
  CHECK(err.empty());
}

TEST_CASE("filter: stop_when reads the input no further", "[filter]") {
  Dir d;
  std::string text;
  for (int i = 0; i < 200000; ++i) text += "G1 X" + std::to_string(i) + "\n";  // ~2 MB: several blocks
  FilterOptions o;
  o.file = d.file("big.gcode", text);
  o.output = d.path + "/out.gcode";
  Filter run(o, gcode::PipelineOptions{.layers = false});
  std::uint64_t lines = 0;
  gctest::FnStage count([&](const gcode::TrackedLine& t, gcode::Emitter& out) {
    ++lines;
    out.pass(t);
  });
  run.add(count);
  run.stop_when([&] { return lines > 0; });
  run.write();
  std::string out = gctest::read_file(o.output);
  CHECK(out.size() < text.size() / 2);
  CHECK(!out.empty());
  // A prefix of whole lines: the line the last read cut off is no line
  // (it was read as a last line without newline: "G1 X4593" for X45937).
  CHECK(text.compare(0, out.size(), out) == 0);
  CHECK(out.back() == '\n');
}

TEST_CASE("filter: the bed from the file's config at either end", "[filter]") {
  Dir d;
  FilterOptions o;
  o.file = d.file("prusa.gcode", layers(2) + std::string(300000, ';') + "\n; bed_shape = 0x0,250x0,250x210,0x210\n");
  Filter run(o);
  gcode::PrintArea area = run.print_area();
  CHECK(area.has_bed);
  CHECK(area.bed.max_x == 250);
  CHECK(area.bed.max_y == 210);
  FilterOptions head;
  const std::string text = "; bed_shape = 0x0,220x0,220x220,0x220\n" + layers(2);
  head.output = d.path + "/out.gcode";
  gctest::with_piped_stdin(text, [&] {
    Filter piped(head);
    gcode::PrintArea a = piped.print_area();
    CHECK(a.has_bed);
    CHECK(a.bed.max_x == 220);
    piped.write();
  });
  CHECK(gctest::read_file(head.output) == text);  // the header read ahead is written too
}

TEST_CASE("filter: a second file is written whole, or to standard output", "[filter]") {
  Dir d;
  const std::string path = d.path + "/picture.svg";
  gcode::cli::write_output_file(path, [](gcode::OutputBuffer& out) {
    out.write("<svg>");
    out.write("</svg>\n");
  });
  CHECK(gctest::read_file(path) == "<svg></svg>\n");
  CHECK(gctest::stdout_of([] { gcode::cli::write_output_file("", [](gcode::OutputBuffer& out) { out.write("x\n"); }); }) ==
        "x\n");
}
