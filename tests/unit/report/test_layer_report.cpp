// gc-layers' reports (report/layer_report.hpp): the JSON document parses and
// holds the table's figures (schema, regions, layers, features, summary,
// bounds; times only with --time), names are escaped; the text table has a
// row per region and the summary lines.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <string>

#include "gcode/pipeline/pipeline.hpp"
#include "gcode/report/layer_report.hpp"
#include "test_support.hpp"

using gcode::LayerTable;
using gcode::ReportOptions;

namespace {

const char* kTwo =
    "M82\nG28\nG92 E0\n"
    ";LAYER:0\n;TYPE:WALL-OUTER\nG1 Z0.2 F600\nG1 X10 Y10 E1 F1200\n;TYPE:FILL\nG1 X20 Y10 E2.5\n"
    ";LAYER:1\nG1 Z0.4\nG1 X20 Y20 E3.5\nG1 E3 F2100\n"
    "G1 X0 Y0 F9000\nM84\n";

struct Report {
  std::string text;
  nlohmann::json json;
};

Report report(const char* gcode, ReportOptions options, bool times = false) {
  gcode::LayerMarkers markers;
  gcode::Pipeline pipeline(markers);
  LayerTable table;
  gcode::LayerTimer timer;
  pipeline.add(table);
  if (times) pipeline.add(timer);
  pipeline.run_text(gcode);
  options.mode = pipeline.tracker().mode();
  if (times) options.times = &timer.times();
  Report r;
  r.text = gcode::layer_table_text(table, pipeline.tracker(), options);
  std::string json = gcode::layer_table_json(table, pipeline.tracker(), options);
  r.json = nlohmann::json::parse(json);
  return r;
}

}  // namespace

TEST_CASE("layer report: the JSON document holds the table", "[layer_report]") {
  ReportOptions o;
  o.file_name = "two \"layers\"\n.gcode";
  Report r = report(kTwo, o);
  const nlohmann::json& j = r.json;
  CHECK(j["schema"] == "gc-layers/1");
  CHECK(j["file"] == "two \"layers\"\n.gcode");  // escaped, and read back
  CHECK(j["layer_mode"] == "markers");
  CHECK(j["start_code"]["first_line"] == 1);
  CHECK(j["start_code"]["last_line"] == 3);
  CHECK(j["start_code"]["byte_begin"] == 0);
  CHECK(j["start_code"]["byte_end"] == 15);
  REQUIRE(j["layers"].size() == 2);
  const nlohmann::json& l1 = j["layers"][0];
  CHECK(l1["layer"] == 1);
  CHECK(l1["slicer_layer"] == 0);
  CHECK(l1["z"] == 0.2);
  CHECK(l1["first_line"] == 4);
  CHECK(l1["last_line"] == 9);
  CHECK(l1["features"] == nlohmann::json::array({"WALL-OUTER", "FILL"}));
  CHECK(l1["filament_mm"] == 2.5);
  CHECK(l1["extruded_mm"] == 2.5);
  CHECK(l1["moves"] == 3);
  CHECK(l1["empty"] == false);
  CHECK_FALSE(l1.contains("time_s"));
  const nlohmann::json& l2 = j["layers"][1];
  CHECK(l2["layer"] == 2);
  CHECK(l2["z"] == 0.4);
  CHECK(l2["height"] == 0.2);
  CHECK(l2["features"] == nlohmann::json::array({"FILL"}));
  // The end code: everything after the last extrusion (the retraction on).
  CHECK(j["end_code"]["first_line"] == 13);
  CHECK(j["end_code"]["last_line"] == 15);
  CHECK(j["end_code"]["byte_end"] == std::string(kTwo).size());
  const nlohmann::json& s = j["summary"];
  CHECK(s["layers"] == 2);
  CHECK(s["filament_mm"] == 3.5);
  CHECK(s["net_filament_mm"] == 3.0);  // the final retraction subtracted
  CHECK(s["lines"] == 15);
  CHECK(s["bytes"] == std::string(kTwo).size());
  CHECK(s["density_g_cm3"] == 1.24);
  CHECK(s["filament_diameter_mm"] == 1.75);
  // The first extrusion starts where G28 left the head.
  CHECK(s["bounds"]["min"] == nlohmann::json::array({0.0, 0.0, 0.2}));
  CHECK(s["bounds"]["max"] == nlohmann::json::array({20.0, 20.0, 0.4}));
  CHECK_FALSE(s.contains("time_s"));
  // 3.5 mm of 1.75 mm filament at 1.24 g/cm3, written with four decimals.
  CHECK(s["filament_g"].get<double>() == 0.0104);
}

TEST_CASE("layer report: with times, every region, layer and the total have them", "[layer_report]") {
  Report r = report(kTwo, {}, true);
  const nlohmann::json& j = r.json;
  double start = j["start_code"]["time_s"], end = j["end_code"]["time_s"];
  double l1 = j["layers"][0]["time_s"], l2 = j["layers"][1]["time_s"];
  CHECK(start == Approx(10).margin(0.001));  // G28
  CHECK(j["layers"][0]["cumulative_s"].get<double>() == Approx(start + l1).margin(0.002));
  CHECK(j["layers"][1]["cumulative_s"].get<double>() == Approx(start + l1 + l2).margin(0.002));
  CHECK(j["summary"]["time_s"].get<double>() == Approx(start + l1 + l2 + end).margin(0.003));
  CHECK(j["summary"]["time"] == gcode::format_duration(j["summary"]["time_s"].get<double>()));
  CHECK(gcode::format_duration(3725.5) == "1:02:06");
  CHECK(gcode::format_duration(-3) == "0:00:00");
  CHECK(r.text.find("print time: ") != std::string::npos);
  CHECK(r.text.find("cumul.") != std::string::npos);
}

TEST_CASE("layer report: the text table", "[layer_report]") {
  ReportOptions o;
  o.file_name = "two.gcode";
  Report r = report(kTwo, o);
  std::vector<std::string> lines = gctest::split_lines(r.text);
  REQUIRE(lines.size() >= 8);
  CHECK(lines[0].find("layer") != std::string::npos);
  CHECK(lines[0].find("features") != std::string::npos);
  CHECK(lines[0].find("time") == std::string::npos);
  CHECK(lines[1].rfind("start", lines[1].find_first_not_of(' ')) != std::string::npos);
  CHECK(lines[1].find("1-3") != std::string::npos);
  CHECK(lines[1].find("0-15") != std::string::npos);
  CHECK(lines[2].find("0.200") != std::string::npos);
  CHECK(lines[2].find("4-9") != std::string::npos);
  CHECK(lines[2].find("WALL-OUTER,FILL") != std::string::npos);
  CHECK(lines[3].find("0.400") != std::string::npos);
  CHECK(lines[4].find("end") != std::string::npos);
  CHECK(lines[4].find("13-15") != std::string::npos);
  CHECK(r.text.find("\n2 layers (from slicer markers), 15 lines, " + std::to_string(std::string(kTwo).size()) +
                    " bytes\n") != std::string::npos);
  CHECK(r.text.find("filament: 3.5 mm = 0.00 m, 0.01 g at 1.24 g/cm3, 1.75 mm (layers; whole file net 3.0 mm)\n") !=
        std::string::npos);
  CHECK(r.text.find("extrusion bounds: X 0.000..20.000  Y 0.000..20.000  Z 0.200..0.400\n") != std::string::npos);
}

TEST_CASE("layer report: a file without layers", "[layer_report]") {
  Report r = report("G28\nM84\n", {});
  CHECK(r.json["layers"].empty());
  CHECK(r.json["summary"]["bounds"].is_null());
  CHECK(r.json["summary"]["layers"] == 0);
  CHECK(r.text.find("extrusion bounds") == std::string::npos);
  CHECK(r.text.find("\n0 layers (") != std::string::npos);
}

TEST_CASE("layer report: layers found by Z say so", "[layer_report]") {
  std::string text = "G28\n";
  for (int i = 1; i <= 4; ++i)
    text += "G1 Z" + std::to_string(i * 0.2).substr(0, 3) + "\nG1 X" + std::to_string(10 * i) + " Y5 E" + std::to_string(i) + "\n";
  Report r = report(text.c_str(), {});
  CHECK(r.json["layer_mode"] == "heuristic");
  CHECK(r.text.find("(found by Z, no layer markers)") != std::string::npos);
}
