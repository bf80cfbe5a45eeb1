// gc-swap-layer on the fixture pairs (tests/fixtures/pairs), checked by the
// independent splice checker (tests/support/splice_check.hpp): which pieces of
// which file make the output, with which Z shift and extrusion factor, and
// seams that keep E, modes, temperatures and the printed part intact; heights
// after skips and repeats; bad input, -i, CRLF, --help and the man page.
#include <catch2/catch.hpp>

#include <filesystem>

#include "splice_check.hpp"
#include "test_support.hpp"

using gctest::quote;
using gctest::read_file;
using gctest::pair_file;
using gctest::pair_part;
using gctest::run;

namespace {

constexpr int kEnd = gctest::kToEnd;
double height(const std::string& name, int layer) { return pair_file(name).height(layer); }

std::string swap(const std::string& args) { return gctest::tool_command("gc-swap-layer", args); }

gctest::RunResult swap_on(const std::string& name, const std::string& args) {
  return run(swap(args + " " + quote(pair_file(name).path)));
}

gctest::SpliceCheck checked(const std::string& out, const std::vector<gctest::SpliceSegment>& segments) {
  gctest::SpliceCheck c = gctest::check_splice(out, segments);
  INFO(c.first_failure());
  REQUIRE(c.failures.empty());
  return c;
}

std::string with(const std::string& name) { return quote(pair_file(name).path); }

const std::string kCura = "cura_block_0.2_infill20.gcode";
const std::string kCuraDense = "cura_block_0.2_infill60.gcode";
const std::string kPrusa = "prusa_block_0.2_infill20.gcode";
const std::string kPrusaDense = "prusa_block_0.2_infill60_220c_k006.gcode";

}  // namespace

TEST_CASE("gc-swap-layer --repeat prints a layer again and raises the rest by its height", "[gc-swap-layer]") {
  for (const std::string& name : {kCura, kPrusa}) {
    INFO(name);
    const double h = height(name, 5);
    auto r = swap_on(name, "--repeat 5");
    REQUIRE(r.status == 0);
    CHECK(r.err == "");
    gctest::SpliceCheck c =
        checked(r.out, {pair_part(name, 0, 6), pair_part(name, 5, 6, h), pair_part(name, 6, kEnd, h)});
    CHECK(c.seams.size() == 2);
    CHECK(c.top_z == Approx(pair_file(name).top + h));  // the print is one layer taller
    auto three = swap_on(name, "--repeat 5x3");
    REQUIRE(three.status == 0);
    gctest::SpliceCheck c3 =
        checked(three.out, {pair_part(name, 0, 6), pair_part(name, 5, 6, h), pair_part(name, 5, 6, 2 * h),
                            pair_part(name, 5, 6, 3 * h), pair_part(name, 6, kEnd, 3 * h)});
    CHECK(c3.top_z == Approx(pair_file(name).top + 3 * h));
  }
}

TEST_CASE("gc-swap-layer --skip leaves layers out and lowers the rest by their thickness", "[gc-swap-layer]") {
  for (const std::string& name : {kCura, kPrusa}) {
    INFO(name);
    const double removed = height(name, 5) + height(name, 6) + height(name, 7);
    auto r = swap_on(name, "--skip 5-7");
    REQUIRE(r.status == 0);
    gctest::SpliceCheck c = checked(r.out, {pair_part(name, 0, 5), pair_part(name, 8, kEnd, -removed)});
    CHECK(c.seams.size() == 1);
    CHECK(c.top_z == Approx(pair_file(name).top - removed));  // exactly the removed thickness lower
  }
}

TEST_CASE("gc-swap-layer --skip --keep-z keeps every Z and scales the next layer's extrusion", "[gc-swap-layer]") {
  for (const std::string& name : {kCura, kPrusa}) {
    INFO(name);
    auto r = swap_on(name, "--skip 5-7 --keep-z");
    REQUIRE(r.status == 0);
    CHECK(r.err.find("over-extrudes by design") != std::string::npos);
    // Layer 8 carries its own 0.2 mm and the 0.6 mm left out: x4.
    gctest::SpliceCheck c =
        checked(r.out, {pair_part(name, 0, 5), pair_part(name, 8, 9, 0, 4), pair_part(name, 9, kEnd)});
    CHECK(c.top_z == Approx(pair_file(name).top));
  }
}

TEST_CASE("gc-swap-layer --layer --with replaces layers by the other file's at the same Z", "[gc-swap-layer]") {
  for (auto [name, other] : {std::pair{kCura, kCuraDense}, std::pair{kPrusa, kPrusaDense}}) {
    INFO(name << " with " << other);
    auto r = swap_on(name, "--layer 5-9 --with " + with(other));
    REQUIRE(r.status == 0);
    // Consecutive layers of the other file follow each other without a seam.
    gctest::SpliceCheck c = checked(r.out, {pair_part(name, 0, 5), pair_part(other, 5, 10), pair_part(name, 10, kEnd)});
    CHECK(c.seams.size() == 2);
  }
  // The other file's temperature for its layers, the input's again after them.
  auto r = swap_on(kPrusa, "--layer 5-9 --with " + with(kPrusaDense));
  gctest::SpliceCheck c =
      checked(r.out, {pair_part(kPrusa, 0, 5), pair_part(kPrusaDense, 5, 10), pair_part(kPrusa, 10, kEnd)});
  CHECK(c.seams.at(0).after.hotend_target[0] == 220);
  CHECK(c.seams.at(1).after.hotend_target[0] == 215);
  auto& first = c.seams.at(0).lines;
  CHECK(std::find(first.begin(), first.end(), "M900 K0.06") != first.end());
  auto& back = c.seams.at(1).lines;
  CHECK(std::find(back.begin(), back.end(), "M104 S215") != back.end());  // cooler: not waited for
  CHECK(std::find(back.begin(), back.end(), "M900 K0.04") != back.end());
}

TEST_CASE("gc-swap-layer --with FILE:LAYERS places the named layers at the replaced Z", "[gc-swap-layer]") {
  // Layer 12 (Z 2.4) by layer 6 of the dense file (Z 1.2): 1.2 mm up.
  auto r = swap_on(kCura, "--layer 12 --with " + with(kCuraDense) + ":6");
  REQUIRE(r.status == 0);
  checked(r.out, {pair_part(kCura, 0, 12), pair_part(kCuraDense, 6, 7, 1.2), pair_part(kCura, 13, kEnd)});
  auto by_height = swap_on(kCura, "--layer @2.4 --with " + with(kCuraDense) + ":@1.2");
  CHECK(by_height.out == r.out);
}

TEST_CASE("gc-swap-layer --insert-after prints a block on top of a layer and raises the rest", "[gc-swap-layer]") {
  const std::string tab = "cura_tab_0.2.gcode";
  const double z10 = pair_file(kCura).layers.z[9];
  const double tab_height = pair_file(tab).layers.z.back();
  auto r = swap_on(kCura, "--insert-after 10 --file " + with(tab));
  REQUIRE(r.status == 0);
  gctest::SpliceCheck c =
      checked(r.out, {pair_part(kCura, 0, 11), pair_part(tab, 1, pair_file(tab).layers.count() + 1, z10),
                      pair_part(kCura, 11, kEnd, tab_height)});
  CHECK(c.top_z == Approx(pair_file(kCura).top + tab_height));
}

TEST_CASE("gc-swap-layer applies several edits in layer order", "[gc-swap-layer]") {
  auto r = swap_on(kCura, "--repeat 7x2 --skip 3 --layer 12-13 --with " + with(kCuraDense));
  REQUIRE(r.status == 0);
  // Layer 3 out (-0.2), layer 7 twice more (+0.4): +0.2 from layer 8 on.
  checked(r.out,
          {pair_part(kCura, 0, 3), pair_part(kCura, 4, 8, -0.2), pair_part(kCura, 7, 8, 0), pair_part(kCura, 7, 8, 0.2),
           pair_part(kCura, 8, 12, 0.2), pair_part(kCuraDense, 12, 14, 0.2), pair_part(kCura, 14, kEnd, 0.2)});
}

TEST_CASE("gc-swap-layer rewrites a file in the other E mode into the input's", "[gc-swap-layer]") {
  auto r = swap_on(kCura, "--layer 8 --with " + with("cura_block_0.2_infill60_rel.gcode"));
  REQUIRE(r.status == 0);
  CHECK(r.err.find("uses relative E and the output absolute") != std::string::npos);
  gctest::SpliceSegment block = pair_part("cura_block_0.2_infill60_rel.gcode", 8, 9);
  block.e_converted = true;
  checked(r.out, {pair_part(kCura, 0, 8), block, pair_part(kCura, 9, kEnd)});
  CHECK(r.out.find("M83") == std::string::npos);
}

TEST_CASE("gc-swap-layer on standard input, with CRLF endings, and -i", "[gc-swap-layer]") {
  auto piped = run(swap("--repeat 5 -"), pair_file(kCura).text);
  REQUIRE(piped.status == 0);
  CHECK(piped.out == swap_on(kCura, "--repeat 5").out);

  std::string crlf;
  for (char ch : pair_file(kCura).text) crlf += ch == '\n' ? std::string("\r\n") : std::string(1, ch);
  auto r = run(swap("--repeat 5"), crlf);
  REQUIRE(r.status == 0);
  for (const std::string& l : gctest::split_lines(r.out)) REQUIRE(l.substr(l.size() - 2) == "\r\n");

  std::string dir = gctest::temp_dir();
  std::string copy = dir + "/part.gcode";
  gctest::write_file(copy, pair_file(kCura).text);
  auto bad = run(swap("-i --skip 80 " + quote(copy)));
  CHECK(bad.status == 1);
  CHECK(read_file(copy) == pair_file(kCura).text);  // not replaced after an error
  auto good = run(swap("-i --repeat 5 " + quote(copy)));
  CHECK(good.status == 0);
  CHECK(read_file(copy) == swap_on(kCura, "--repeat 5").out);
  std::filesystem::remove_all(dir);
}

TEST_CASE("gc-swap-layer refuses what the input cannot meet", "[gc-swap-layer][errors]") {
  auto beyond = swap_on(kCura, "--skip 80");
  CHECK(beyond.status == 1);
  CHECK(beyond.err.find("--skip 80: the input has 20 layers") != std::string::npos);
  auto height_missing = swap_on(kCura, "--repeat @9");
  CHECK(height_missing.status == 1);
  CHECK(height_missing.err.find("no layer of the input is at that height") != std::string::npos);
  auto other = swap_on(kCura, "--layer 5 --with " + with(kPrusaDense));
  CHECK(other.status == 1);
  CHECK(other.err.find("does not lie where the input prints") != std::string::npos);
  auto no_z = run(swap("--layer 12 --with " + with(kCura) + " " +
                       quote(gctest::fixture_path("pairs/cura_block_0.1_infill20.gcode"))));
  CHECK(no_z.status == 1);
  CHECK(no_z.err.find("has no layer at Z 1.3") != std::string::npos);
  auto short_list = swap_on(kCura, "--layer 5-6 --with " + with(kCuraDense) + ":5");
  CHECK(short_list.status == 1);
  const std::vector<std::string> usage = {std::string(""), "--layer 5 " + with(kCura), "--with x.gcode " + with(kCura),
                                  "--skip 5 --layer 5 --with x.gcode " + with(kCura), "--keep-z " + with(kCura),
                                  "--repeat 5x0 " + with(kCura), "--repeat 5-6 " + with(kCura),
                                  "--skip 5 --repeat 5 " + with(kCura), "--insert-after 3 " + with(kCura),
                                  "--skip 0 " + with(kCura), "--skip 3 --lift -2 " + with(kCura),
                                  "--skip 3 -i", "--layer 5 --with - " + with(kCura)};
  for (const std::string& args : usage) {
    INFO(args);
    auto r = run(swap(args));
    CHECK(r.status == 2);
    CHECK(r.err.find("gc-swap-layer: ") == 0);
    CHECK(r.out == "");
  }
}


TEST_CASE("gc-swap-layer --help and the man page name the same options", "[gc-swap-layer][docs]") {
  auto help = run(swap("--help"));
  REQUIRE(help.status == 0);
  std::string man = read_file(std::string(GC_FIXTURES_DIR) + "/../../man/gc-swap-layer.1");
  CHECK(gctest::long_options(help.out) == gctest::long_options(man));
  CHECK(gctest::long_options(help.out).count("--keep-z") == 1);
  CHECK(man.find(".SH EXIT STATUS") != std::string::npos);
}
