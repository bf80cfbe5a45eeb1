// gc-relayer on the fixture pairs (tests/fixtures/pairs: one box sliced
// twice with one setting changed), checked by the independent splice checker
// (tests/support/splice_check.hpp): the old file up to the join, the new one
// from the layer the rules choose, seams that keep E, modes, temperatures and
// the printed part intact; resume sequences; bad input; --help and the man page.
#include <catch2/catch.hpp>

#include <filesystem>

#include "splice_check.hpp"
#include "test_support.hpp"

using gctest::quote;
using gctest::read_file;
using gctest::run;

namespace {

using Source = gctest::PairFile;

const Source& pair(const std::string& name) { return gctest::pair_file(name); }
int first_above(const Source& s, double z) { return s.first_above(z); }
gctest::SpliceSegment part(const std::string& name, int first_layer, int end_layer, double shift = 0,
                           double scale = 1) {
  return gctest::pair_part(name, first_layer, end_layer, shift, scale);
}
// To the end of the file, end code included.
gctest::SpliceSegment rest(const std::string& name, int first_layer) {
  return gctest::pair_part(name, first_layer, gctest::kToEnd);
}

std::string relayer(const std::string& args) { return gctest::tool_command("gc-relayer", args); }

gctest::RunResult join(const std::string& old_name, const std::string& new_name, const std::string& args) {
  return run(relayer(args + " " + quote(pair(new_name).path)), pair(old_name).text);
}

void require_clean(const gctest::SpliceCheck& c) {
  INFO(c.first_failure());
  REQUIRE(c.failures.empty());
}

}  // namespace

TEST_CASE("gc-relayer --at-z with equal layer heights: old layers to the height then the new file", "[gc-relayer]") {
  for (auto [old_name, new_name] : {std::pair{"cura_block_0.2_infill20.gcode", "cura_block_0.2_infill60.gcode"},
                                    std::pair{"prusa_block_0.2_infill20.gcode",
                                              "prusa_block_0.2_infill60_220c_k006.gcode"}}) {
    INFO(old_name << " -> " << new_name);
    auto r = join(old_name, new_name, "--at-z 2");
    REQUIRE(r.status == 0);
    const Source& o = pair(old_name);
    int kept = first_above(o, 2) - 1;
    int k = first_above(pair(new_name), 2);
    REQUIRE(kept == 10);
    gctest::SpliceCheck c = gctest::check_splice(r.out, {part(old_name, 0, kept + 1), rest(new_name, k)});
    require_clean(c);
    REQUIRE(c.seams.size() == 1);
    CHECK(r.err.find("layers 1-10 (to Z 2) are kept") != std::string::npos);
    CHECK(r.err.find("from its layer 11 (Z 2.2)") != std::string::npos);
  }
}

TEST_CASE("gc-relayer carries the new file's temperature and pressure advance across the seam", "[gc-relayer]") {
  auto r = join("prusa_block_0.2_infill20.gcode", "prusa_block_0.2_infill60_220c_k006.gcode", "--at-z 2");
  REQUIRE(r.status == 0);
  gctest::SpliceCheck c = gctest::check_splice(
      r.out, {part("prusa_block_0.2_infill20.gcode", 0, 11), rest("prusa_block_0.2_infill60_220c_k006.gcode", 11)});
  require_clean(c);
  const auto& seam = c.seams.at(0).lines;
  auto has = [&](const std::string& l) { return std::find(seam.begin(), seam.end(), l) != seam.end(); };
  CHECK(has("M109 S220"));   // hotter: waited for before the block
  CHECK(has("M900 K0.06"));  // the new profile's linear advance
  CHECK_FALSE(has("M221 S95"));  // the same flow in both: not repeated
  CHECK(c.seams.at(0).after.hotend_target[0] == 220);
  // Nothing of the new file's start code but the carried settings.
  std::size_t checks = 0, homes = 0;
  for (const std::string& l : gctest::split_lines(r.out)) {
    checks += l.rfind("M862.3", 0) == 0 ? 1 : 0;
    homes += l.rfind("G28", 0) == 0 ? 1 : 0;
  }
  CHECK(checks == 1);
  CHECK(homes == 1);
}

TEST_CASE("gc-relayer onto thinner new layers goes on from the first one above the print", "[gc-relayer]") {
  for (auto [old_name, new_name] : {std::pair{"cura_block_0.2_infill20.gcode", "cura_block_0.1_infill20.gcode"},
                                    std::pair{"prusa_block_0.2_infill20.gcode", "prusa_block_0.1_infill20.gcode"}}) {
    INFO(old_name << " -> " << new_name);
    auto r = join(old_name, new_name, "--at-z 2");
    REQUIRE(r.status == 0);
    int k = first_above(pair(new_name), 2);
    CHECK(pair(new_name).layers.z[static_cast<std::size_t>(k - 1)] == Approx(2.1));
    require_clean(gctest::check_splice(r.out, {part(old_name, 0, 11), rest(new_name, k)}));
  }
}

TEST_CASE("gc-relayer onto thicker new layers leaves out the covered one and fills the gap at half height",
          "[gc-relayer]") {
  // The old file printed to Z 2.1 in 0.1 mm layers; the new one has 2.2 (only
  // 0.1 of its 0.2 mm free: covered) and 2.4 (0.3 above the print: a gap of
  // 0.1 under it). Its layer at 2.4 is printed first at Z 2.2 with half its
  // extrusion, then the new file goes on from that layer.
  for (auto [old_name, new_name] : {std::pair{"cura_block_0.1_infill20.gcode", "cura_block_0.2_infill20.gcode"},
                                    std::pair{"prusa_block_0.1_infill20.gcode", "prusa_block_0.2_infill20.gcode"}}) {
    INFO(old_name << " -> " << new_name);
    auto r = join(old_name, new_name, "--at-z 2.1");
    REQUIRE(r.status == 0);
    const Source& n = pair(new_name);
    int covered = first_above(n, 2.1);
    REQUIRE(n.layers.z[static_cast<std::size_t>(covered - 1)] == Approx(2.2));
    int next = covered + 1;
    int old_kept = first_above(pair(old_name), 2.1) - 1;
    gctest::SpliceCheck c = gctest::check_splice(
        r.out, {part(old_name, 0, old_kept + 1), part(new_name, next, next + 1, -0.2, 0.5), rest(new_name, next)});
    require_clean(c);
    CHECK(c.seams.size() == 2);
    CHECK(r.err.find("layer " + std::to_string(covered) + " left out: already covered") != std::string::npos);
    CHECK(r.err.find("printed first at Z 2.2 with its extrusion x0.5") != std::string::npos);
  }
}

TEST_CASE("gc-relayer --at-layer joins after the old file's layer N", "[gc-relayer]") {
  auto by_layer = join("cura_block_0.2_infill20.gcode", "cura_block_0.2_infill60.gcode", "--at-layer 10");
  auto by_z = join("cura_block_0.2_infill20.gcode", "cura_block_0.2_infill60.gcode", "--at-z 2.1");
  REQUIRE(by_layer.status == 0);
  CHECK(by_layer.out == by_z.out);
  // After the old file's last layer: the old end code goes, the new file has nothing above.
  auto top = join("cura_block_0.2_infill20.gcode", "cura_block_0.2_infill60.gcode", "--at-layer 20");
  CHECK(top.status == 1);
  CHECK(top.err.find("no layer above Z 4") != std::string::npos);
}

TEST_CASE("gc-relayer rewrites a new file in the other E mode and says so", "[gc-relayer]") {
  auto r = join("cura_block_0.2_infill20.gcode", "cura_block_0.2_infill60_rel.gcode", "--at-z 2");
  REQUIRE(r.status == 0);
  CHECK(r.err.find("uses relative E and the output absolute") != std::string::npos);
  gctest::SpliceSegment n = rest("cura_block_0.2_infill60_rel.gcode", 11);
  n.e_converted = true;  // moves compared by the filament they push
  require_clean(gctest::check_splice(r.out, {part("cura_block_0.2_infill20.gcode", 0, 11), n}));
  // Every E in the output is absolute: no M83 was written.
  CHECK(r.out.find("M83") == std::string::npos);
}

TEST_CASE("gc-relayer refuses what it cannot join", "[gc-relayer][errors]") {
  const std::string cura = "cura_block_0.2_infill20.gcode", dense = "cura_block_0.2_infill60.gcode";
  auto low = join(cura, dense, "--at-z 0.1");
  CHECK(low.status == 1);
  CHECK(low.err.find("--at-z 0.1: the input's first layer is higher (Z 0.2)") != std::string::npos);
  auto beyond = join(cura, dense, "--at-layer 80");
  CHECK(beyond.status == 1);
  CHECK(beyond.err.find("--at-layer 80: the input has 20 layers") != std::string::npos);
  auto other = join(cura, "prusa_block_0.2_infill60_220c_k006.gcode", "--at-z 2");
  CHECK(other.status == 1);
  CHECK(other.err.find("does not lie where the input prints") != std::string::npos);
  auto missing = run(relayer("--at-z 2 /no/such.gcode"), pair(cura).text);
  CHECK(missing.status == 1);
  const std::vector<std::string> usage = {"",
                                         "--at-z 2 --at-layer 3 x.gcode",
                                         "--at-z 2",
                                         "--at-z 2 -",
                                         "--purge 5 --at-z 2 x.gcode",
                                         "--at-z -1 x.gcode",
                                         "--at-layer 0 x.gcode",
                                         "--lift -1 --at-z 2 x.gcode",
                                         "--resume-from-z 2 --purge-at 5 " + quote(pair(cura).path)};
  for (const std::string& args : usage) {
    INFO(args);
    auto r = run(relayer(args), "");
    CHECK(r.status == 2);
    CHECK(r.err.find("gc-relayer: ") == 0);
    CHECK(r.out == "");
  }
}

TEST_CASE("gc-relayer --resume-from-z: heat, lift, declare Z, home X Y, then the first layer above", "[gc-relayer]") {
  // PrusaSlicer writes the bed's size (the purge goes to its front left
  // corner); CuraEngine's command line does not, so the place is given.
  for (auto [name, purge_at] : {std::pair{"prusa_block_0.2_infill20.gcode", ""},
                                std::pair{"cura_block_0.2_infill20.gcode", "--purge-at 5,5 "}}) {
    INFO(name);
    const Source& s = pair(name);
    auto r = run(relayer("--resume-from-z 2.02 --purge 10 " + std::string(purge_at) + quote(s.path)));
    REQUIRE(r.status == 0);
    CHECK(r.err.find("resuming at layer 11 (Z 2.2)") != std::string::npos);
    gctest::SpliceSegment from = rest(name, 11);
    from.seam_extra = 10;  // the purge
    gctest::SpliceCheck c = gctest::check_splice(r.out, {from});
    require_clean(c);
    std::vector<gctest::Replayed> out = gctest::replay_lines(r.out);
    bool heated = false, moved = false, extruded = false;
    for (const gctest::Replayed& l : out) {
      if (l.line.is_g(28)) {
        // Never home Z with a part on the bed, never a bare G28.
        CHECK(l.line.has('X'));
        CHECK(l.line.has('Y'));
        CHECK_FALSE(l.line.has('Z'));
      }
      if (l.line.is_m(109) || l.line.is_m(190)) {
        if (!moved) heated = true;
      }
      if (l.line.is_move() && !moved) {
        moved = true;
        CHECK(heated);  // heating before any move
      }
      if (l.move.extruding && !extruded) {
        extruded = true;
        CHECK(l.move.start[gcode::kZ] == Approx(2.2));  // the first extrusion at the chosen layer's Z
      }
    }
    CHECK(extruded);
    // Z was declared after a lift from the measured height.
    CHECK(r.out.find("G91\nG1 Z2 F600\nG90\nG92 Z4.02\nG28 X Y\n") != std::string::npos);
  }
}

TEST_CASE("gc-relayer --list-candidates prints the two layers nearest a height", "[gc-relayer]") {
  auto r = run(relayer("--list-candidates 2.02 " + quote(pair("prusa_block_0.2_infill20.gcode").path)));
  REQUIRE(r.status == 0);
  CHECK(r.out.find("layer 10  Z 2  height 0.2  0.02 mm below 2.02: printed\n") == 0);
  CHECK(r.out.find("layer 11  Z 2.2  height 0.2  0.18 mm above 2.02") != std::string::npos);
  auto top = run(relayer("--list-candidates 9 " + quote(pair("prusa_block_0.2_infill20.gcode").path)));
  CHECK(top.out.find("no layer above Z 9") != std::string::npos);
  auto no_bed = run(relayer("--resume-from-z 2 --purge 5 " + quote(pair("cura_block_0.2_infill20.gcode").path)));
  CHECK(no_bed.status == 1);
  CHECK(no_bed.err.find("give --purge-at X,Y") != std::string::npos);
  auto over = run(relayer("--resume-from-z 2 --purge 5 --purge-at 110,110 " +
                          quote(pair("cura_block_0.2_infill20.gcode").path)));
  CHECK(over.status == 1);
  CHECK(over.err.find("is above the part") != std::string::npos);
  auto done = run(relayer("--resume-from-z 9 " + quote(pair("prusa_block_0.2_infill20.gcode").path)));
  CHECK(done.status == 1);
  CHECK(done.err.find("nothing to resume: the file's last layer is at Z 4") != std::string::npos);
}

TEST_CASE("gc-relayer -o writes the file", "[gc-relayer]") {
  std::string dir = gctest::temp_dir();
  std::string out = dir + "/joined.gcode";
  auto r = join("cura_block_0.2_infill20.gcode", "cura_block_0.2_infill60.gcode", "--at-z 2 -q -o " + quote(out));
  CHECK(r.status == 0);
  CHECK(r.out == "");
  CHECK(r.err == "");
  CHECK(read_file(out) == join("cura_block_0.2_infill20.gcode", "cura_block_0.2_infill60.gcode", "--at-z 2").out);
  std::filesystem::remove_all(dir);
}


TEST_CASE("gc-relayer --help and the man page name the same options", "[gc-relayer][docs]") {
  auto help = run(relayer("--help"));
  REQUIRE(help.status == 0);
  std::string man = read_file(std::string(GC_FIXTURES_DIR) + "/../../man/gc-relayer.1");
  CHECK(gctest::long_options(help.out) == gctest::long_options(man));
  CHECK(gctest::long_options(help.out).count("--resume-from-z") == 1);
  CHECK(man.find(".SH EXIT STATUS") != std::string::npos);
}
