// gc-layers on real slicer output: layer counts, Z, filament against the
// slicers' own figures, lossless cutting, and errors.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <regex>
#include <set>
#include <vector>

#include "test_support.hpp"

using gctest::fixture_path;
using gctest::quote;
using gctest::read_file;
using gctest::run;
using Json = nlohmann::json;

namespace {


Json layers_json(const std::string& path) {
  auto r = run(gctest::tool_command("gc-layers", "--json " + quote(path)));
  REQUIRE(r.status == 0);
  return Json::parse(r.out);
}

int count_lines_starting(const std::string& text, const std::string& prefix) {
  int n = 0;
  for (const auto& l : gctest::split_lines(text))
    if (l.rfind(prefix, 0) == 0) ++n;
  return n;
}

// The layers a slicer wrote, counted without the library's tracker: the
// fixture's expected data where it has some (the slicer's own count, see
// tests/fixtures/sources/README.md), else its markers, or for unmarked files
// the distinct heights at which it extrudes.
int expected_layers(const std::string& name, const std::string& text) {
  if (Json e = gctest::expected_data(name); !e.is_null()) return e["layer_count"].get<int>();
  if (int n = count_lines_starting(text, ";LAYER_CHANGE"); n > 0) return n;
  if (int n = count_lines_starting(text, ";LAYER:"); n > 0) return n;
  std::set<long> heights;
  for (const auto& m : gctest::replay_moves(text))
    if (m.move.extruding) heights.insert(std::lround(m.move.start[gcode::kZ] * 1000));
  return static_cast<int>(heights.size());
}

// The slicer's own "filament used" in mm, or a negative number if none.
double slicer_filament_mm(const std::string& text) {
  std::smatch m;
  if (std::regex_search(text, m, std::regex(";Filament used: ([0-9.]+)m"))) return std::stod(m[1]) * 1000;
  if (std::regex_search(text, m, std::regex("; filament used \\[mm\\] = ([0-9.]+)"))) return std::stod(m[1]);
  if (std::regex_search(text, m, std::regex("; filament used = ([0-9.]+)mm"))) return std::stod(m[1]);
  return -1;
}

}  // namespace

TEST_CASE("gc-layers finds the layers each slicer wrote, on every fixture", "[gc-layers][fixtures]") {
  for (const auto& name : gctest::fixture_names()) {
    INFO(name);
    std::string text = read_file(fixture_path(name));
    Json j = layers_json(fixture_path(name));
    CHECK(j["layers"].size() == static_cast<std::size_t>(expected_layers(name, text)));
    CHECK(j["summary"]["layers"] == j["layers"].size());
    CHECK(j["summary"]["bytes"] == text.size());
    // Regions tile the file: each starts where the previous ended.
    std::uint64_t at = j["start_code"]["byte_end"];
    for (const auto& l : j["layers"]) {
      CHECK(l["byte_begin"] == at);
      at = l["byte_end"];
    }
    CHECK(j["end_code"]["byte_begin"] == at);
    CHECK(j["end_code"]["byte_end"] == text.size());
  }
}

TEST_CASE("each layer's Z is the slicer's Z: comment", "[gc-layers][fixtures]") {
  for (const auto& name : gctest::fixture_names()) {
    std::string text = read_file(fixture_path(name));
    std::vector<double> zs;
    for (const auto& l : gctest::split_lines(text))
      if (l.rfind(";Z:", 0) == 0) zs.push_back(std::stod(l.substr(3)));
    if (zs.empty()) continue;
    INFO(name);
    Json j = layers_json(fixture_path(name));
    REQUIRE(j["layers"].size() == zs.size());
    for (std::size_t i = 0; i < zs.size(); ++i) CHECK(j["layers"][i]["z"].get<double>() == Approx(zs[i]).margin(1e-6));
  }
}

TEST_CASE("each layer's Z and the filament are the slicer's on the fixtures with expected data", "[gc-layers][fixtures]") {
  int checked = 0;
  for (const auto& name : gctest::fixture_names()) {
    Json e = gctest::expected_data(name);
    if (e.is_null()) continue;
    INFO(name << " (" << e["method"] << ")");
    Json j = layers_json(fixture_path(name));
    // Heights in micrometres (the files write 3 decimals): one comparison that shows both lists.
    std::vector<long> ours, slicer;
    for (const Json& l : j["layers"]) ours.push_back(std::lround(l["z"].get<double>() * 1000));
    for (const Json& z : e["z"]) slicer.push_back(std::lround(z.get<double>() * 1000));
    CHECK(ours == slicer);
    // The start code's purge is no layer, so the layers hold what the slicer counted.
    double expected = e["filament_mm"];
    CHECK(j["summary"]["filament_mm"].get<double>() == Approx(expected).epsilon(0.001));
    ++checked;
  }
  CHECK(checked == 8);
}

TEST_CASE("unmarked and Cura layers sit at the heights they extrude at", "[gc-layers][fixtures]") {
  Json j = layers_json(fixture_path("slic3r_cube_0.2_abs_reprap_skirt.gcode"));
  REQUIRE(j["layer_mode"] == "heuristic");
  for (std::size_t i = 2; i < j["layers"].size(); ++i)
    CHECK(j["layers"][i]["height"].get<double>() == Approx(0.2).margin(1e-6));
  Json c = layers_json(fixture_path("cura_cube_0.2_abs_zhop_skirt.gcode"));
  for (std::size_t i = 0; i < c["layers"].size(); ++i) {
    CHECK(c["layers"][i]["slicer_layer"] == i);
    CHECK(c["layers"][i]["z"].get<double>() == Approx(0.2 * static_cast<double>(i + 1)).margin(1e-6));
  }
}

TEST_CASE("filament in the layers equals the slicer's own figure within 0.1 %", "[gc-layers][fixtures]") {
  for (const auto& name : gctest::fixture_names()) {
    std::string text = read_file(fixture_path(name));
    double expected = slicer_filament_mm(text);
    // Fixtures with expected data are held to it, start-code purge excluded, above.
    if (expected < 0 || !gctest::expected_data(name).is_null()) continue;
    INFO(name);
    Json j = layers_json(fixture_path(name));
    double ours = j["summary"]["filament_mm"];
    CHECK(std::fabs(ours - expected) <= expected * 0.001);
  }
}

// --extract 1- writing every fixture byte for byte: tests/cli/test_conventions.cpp.

TEST_CASE("an extract of a middle range replays exactly the moves of those layers", "[gc-layers][property]") {
  for (const auto& name : gctest::fixture_names()) {
    INFO(name);
    std::string path = fixture_path(name);
    std::string text = read_file(path);
    Json j = layers_json(path);
    int n = static_cast<int>(j["layers"].size());
    int first = n / 3, last = n / 2;
    auto r = run(gctest::tool_command("gc-layers", "--extract " + std::to_string(first) + "-" + std::to_string(last) + " " + quote(path)));
    REQUIRE(r.status == 0);
    // The chosen layers' bytes stand in the output unchanged, and replayed in
    // the output's context their moves equal the input's (position, filament,
    // feed rate; the E coordinate too when E is absolute).
    std::uint64_t begin = j["layers"][first - 1]["byte_begin"], end = j["layers"][last - 1]["byte_end"];
    std::string chosen = text.substr(begin, end - begin);
    std::size_t at_out = r.out.find(chosen);
    REQUIRE(at_out != std::string::npos);
    auto moves_in = [](const std::string& all, std::size_t from, std::size_t to) {
      std::vector<gcode::Move> v;
      auto lines = gctest::split_lines(all);
      std::vector<std::size_t> offsets;
      std::size_t at = 0;
      for (const auto& l : lines) {
        offsets.push_back(at);
        at += l.size();
      }
      for (const auto& m : gctest::replay_moves(all))
        if (offsets[m.line_index] >= from && offsets[m.line_index] < to) v.push_back(m.move);
      return v;
    };
    auto wanted = moves_in(text, begin, end);
    auto got = moves_in(r.out, at_out, at_out + chosen.size());
    REQUIRE(!wanted.empty());
    REQUIRE(got.size() == wanted.size());
    bool absolute_e = !gctest::replay_state(text.substr(0, begin)).relative_e;
    for (std::size_t i = 0; i < wanted.size(); ++i) {
      for (int axis = 0; axis < 3; ++axis) REQUIRE(got[i].end[axis] == Approx(wanted[i].end[axis]).margin(1e-9));
      if (absolute_e) REQUIRE(got[i].end[gcode::kE] == Approx(wanted[i].end[gcode::kE]).margin(1e-9));
      REQUIRE(got[i].filament == Approx(wanted[i].filament).margin(1e-9));
      REQUIRE(got[i].feedrate == Approx(wanted[i].feedrate));
    }
    // Where layers were left out, the bridge lifts above the part before travelling.
    CHECK(r.out.find("; gc-layers: layers 1-" + std::to_string(first - 1) + " left out") != std::string::npos);
  }
}

TEST_CASE("ranges: last N from a pipe, lists, --z-range, --where", "[gc-layers]") {
  std::string path = fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode");
  std::string text = read_file(path);
  auto last3 = run(gctest::tool_command("gc-layers", "--extract -3 -"), text);
  REQUIRE(last3.status == 0);
  auto explicit3 = run(gctest::tool_command("gc-layers", "--extract 98-100 " + quote(path)));
  CHECK(last3.out == explicit3.out);
  auto byz = run(gctest::tool_command("gc-layers", "--z-range 19.55:20 " + quote(path)));
  CHECK(byz.out == explicit3.out);
  auto list = run(gctest::tool_command("gc-layers", "--extract 1,3,5-6 " + quote(path)));
  CHECK(list.status == 0);
  CHECK(list.out.find("; gc-layers: layer 2 left out") != std::string::npos);
  CHECK(list.out.find("; gc-layers: layers 7-100 left out") != std::string::npos);
  Json j = layers_json(path);
  auto where = run(gctest::tool_command("gc-layers", "--where 50 " + quote(path)));
  REQUIRE(where.status == 0);
  CHECK(where.out == std::to_string(j["layers"][49]["first_line"].get<int>()) + " " +
                         std::to_string(j["layers"][49]["last_line"].get<int>()) + " " +
                         std::to_string(j["layers"][49]["byte_begin"].get<int>()) + " " +
                         std::to_string(j["layers"][49]["byte_end"].get<int>()) + "\n");
}

TEST_CASE("CRLF and a missing final newline change nothing but the bytes", "[gc-layers]") {
  std::string text = read_file(fixture_path("slic3r_cube_0.2_abs_reprap_skirt.gcode"));
  std::string crlf;
  for (char c : text) {
    if (c == '\n') crlf += '\r';
    crlf += c;
  }
  crlf.pop_back();
  crlf.pop_back();  // no final newline
  auto all = run(gctest::tool_command("gc-layers", "--extract 1- -"), crlf);
  CHECK(all.out == crlf);
  auto table = run(gctest::tool_command("gc-layers", "--json -"), crlf);
  CHECK(Json::parse(table.out)["layers"].size() == 100);  // the slicer's count: its purge line is start code
  auto some = run(gctest::tool_command("gc-layers", "--extract 5-6 -"), crlf);
  for (const auto& l : gctest::split_lines(some.out)) CHECK((l.size() < 2 || l.substr(l.size() - 2) == "\r\n" || l.back() != '\n'));
}

TEST_CASE("errors: missing layer, empty input, no extrusion, bad options", "[gc-layers][errors]") {
  std::string path = fixture_path("cura_cube_0.2_abs_zhop_skirt.gcode");
  auto missing = run(gctest::tool_command("gc-layers", "--extract 80-120 " + quote(path)));
  CHECK(missing.status == 1);
  CHECK(missing.err.find("layer 80") == std::string::npos);
  CHECK(missing.err.find("layer 120 does not exist") != std::string::npos);
  auto where = run(gctest::tool_command("gc-layers", "--where 101 " + quote(path)));
  CHECK(where.status == 1);
  CHECK(where.err.find("has 100 layers") != std::string::npos);
  // The report, and a cut, which counts layers without the report's table:
  // the same checks, the same count.
  for (const char* args : {"-", "--extract 1- -"}) {
    INFO(args);
    auto empty = run(gctest::tool_command("gc-layers", args), "");
    CHECK(empty.status == 1);
    CHECK(empty.err.find("empty input") != std::string::npos);
    auto none = run(gctest::tool_command("gc-layers", args), "G28\nG1 Z10\n");
    CHECK(none.status == 1);
    CHECK(none.err.find("no extrusion") != std::string::npos);
  }
  CHECK(run(gctest::tool_command("gc-layers", "-v --extract 3-4 " + quote(path))).err.find("wrote 2 of 100 layers") !=
        std::string::npos);
  CHECK(run(gctest::tool_command("gc-layers", "-v --z-range 0:0.6 " + quote(path))).err.find(" of 100 layers") !=
        std::string::npos);
  CHECK(run(gctest::tool_command("gc-layers", "--extract 5-2 " + quote(path))).status == 2);
  CHECK(run(gctest::tool_command("gc-layers", "--extract abc " + quote(path))).status == 2);
  CHECK(run(gctest::tool_command("gc-layers", "--bogus " + quote(path))).status == 2);
  CHECK(run(gctest::tool_command("gc-layers", "/nonexistent/file.gcode")).status == 1);
  CHECK(run(gctest::tool_command("gc-layers", "--layer-marker '(' " + quote(path))).status == 2);
}

TEST_CASE("gc-layers -i rewrites the file atomically and only on success", "[gc-layers]") {
  std::string dir = gctest::temp_dir();
  std::string copy = dir + "/cube.gcode";
  std::string original = read_file(fixture_path("cura_cube_0.2_abs_zhop_skirt.gcode"));
  gctest::write_file(copy, original);
  CHECK(run(gctest::tool_command("gc-layers", "-i --extract 200 " + quote(copy))).status == 1);
  CHECK(read_file(copy) == original);
  REQUIRE(run(gctest::tool_command("gc-layers", "-i --extract 1-10 " + quote(copy))).status == 0);
  std::string cut = read_file(copy);
  CHECK(cut.size() < original.size());
  CHECK(run(gctest::tool_command("gc-layers", "--json " + quote(copy))).out.find("\"layer\": 10,") != std::string::npos);
}

TEST_CASE("a closed pipe ends gc-layers quietly", "[gc-layers]") {
  auto r = run(gctest::tool_command("gc-layers", "--extract 1- " + quote(fixture_path("cura_vase_0.2_spiralize.gcode")) + " | head -c 100"));
  CHECK(r.out.size() == 100);
  CHECK(r.err.empty());
}
