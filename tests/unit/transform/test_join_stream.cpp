// Another file continuing a print as it runs (transform/join_stream.hpp):
// from the printed side a PauseContext gives where the print stands, the
// pumped text is exactly what gc-relayer's plan writes after its join, in
// pieces of one read; and what cannot join says why.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>

#include "gcode/core/number.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "gcode/transform/join_stream.hpp"
#include "gcode/transform/pause_context.hpp"
#include "gcode/transform/relayer.hpp"
#include "gcode/transform/splice.hpp"
#include "test_support.hpp"

namespace {

std::string pair_path(const std::string& name) { return gctest::fixture_path("pairs/" + name); }

// How a print of `text` stands at the start of its layer `layer`: the
// printed side and the byte offset there.
struct Stopped {
  gcode::StreamPoint printed;
  std::uint64_t offset = 0;
};

Stopped stopped_before(const std::string& text, int layer) {
  struct Upto : gcode::Stage {
    int stop = 0;
    bool stopped = false;
    gcode::PauseContext context;
    gcode::MachineState at;
    std::uint64_t offset = 0;
    void line(const gcode::TrackedLine& t, gcode::Emitter& out) override {
      if (!stopped) context.observe(t);
      out.pass(t);
    }
    void layer(const gcode::LayerInfo& info, const gcode::MachineState& before, gcode::Emitter& out) override {
      if (info.index == stop && !stopped) {
        stopped = true;
        at = before;
        offset = info.offset;
      }
      out.layer(info, before);
    }
  } upto;
  upto.stop = layer;
  gcode::LayerMarkers markers;
  gcode::Pipeline p(markers);
  p.add(upto);
  p.run_text(text);
  REQUIRE(upto.stopped);
  return {upto.context.stream_point(upto.at), upto.offset};
}

// gc-relayer's join of `next` onto `old` after its layer `layer`, in the library.
std::string relayed(const std::string& old, const std::string& next, int layer) {
  gctest::OpenedFile f(next);
  gcode::LayerMarkers markers;
  gcode::LayerIndex index(f.fd(), next, markers);
  gcode::RelayerPlan::Options o;
  o.at_layer = layer;
  gcode::RelayerPlan plan(index, o, nullptr);
  gcode::Pipeline p(markers);
  gcode::SpliceStage stage(plan, p.precision(), gcode::SeamOptions{});
  p.add(stage);
  return gctest::run_stages(p, old);
}

}  // namespace

TEST_CASE("join stream: the text after the join is gc-relayer's, a read at a time", "[splice][join]") {
  struct Pair {
    const char* old;
    const char* next;
    int layer;
  };
  for (Pair c : {Pair{"cura_block_0.2_infill20.gcode", "cura_block_0.1_infill20.gcode", 6},
                 Pair{"cura_block_0.1_infill20.gcode", "cura_block_0.2_infill20.gcode", 8},
                 Pair{"cura_block_0.2_infill20.gcode", "cura_block_0.2_infill60_rel.gcode", 3},
                 Pair{"prusa_block_0.2_infill20.gcode", "prusa_block_0.2_infill60_220c_k006.gcode", 10}}) {
    INFO(c.old << " -> " << c.next << " after layer " << c.layer);
    const std::string old = gctest::read_file(pair_path(c.old));
    const std::string next = pair_path(c.next);
    Stopped at = stopped_before(old, c.layer + 1);
    gcode::JoinStream join(next);
    char z[gcode::kMaxNumberChars];
    join.plan(at.printed, 3,
              "the input's layer " + std::to_string(c.layer) + " (Z " +
                  std::string(gcode::number_text(at.printed.top_z, 4, z)) + ")",
              nullptr);
    gcode::Precision precision;
    std::string text;
    std::size_t pumps = 0, most = 0;
    for (std::size_t before = 0; join.pump(text, gcode::SeamOptions{}, precision, nullptr); before = text.size()) {
      ++pumps;
      most = std::max(most, text.size() - before);
    }
    CHECK(pumps > 1);
    CHECK(most <= 70000);  // one read of 64 KiB and its seam
    CHECK(join.bytes_out() == join.bytes());
    const std::string expected = relayed(old, pair_path(c.next), c.layer);
    REQUIRE(expected.size() > at.offset);
    CHECK(old.substr(0, at.offset) + text == expected);
    CHECK(join.printed().top_z == Approx(4.0));  // the box's top, whichever file
    CHECK_FALSE(join.report().empty());
  }
}

TEST_CASE("join stream: what cannot join says why", "[splice][join]") {
  const std::string dir = gctest::temp_dir();
  CHECK_THROWS_WITH(gcode::JoinStream(dir + "/none.gcode"), Catch::Contains("cannot open"));
  CHECK_THROWS_WITH(gcode::JoinStream(dir), Catch::Contains("not a regular file"));
  const std::string old = gctest::read_file(pair_path("cura_block_0.2_infill20.gcode"));
  Stopped at = stopped_before(old, 8);
  {
    gcode::JoinStream tab(pair_path("cura_tab_0.2.gcode"));
    CHECK_THROWS_WITH(tab.plan(at.printed, 3, "", nullptr), Catch::Contains("has no layer above Z 1.4"));
  }
  {
    gcode::JoinStream elsewhere(pair_path("prusa_block_0.2_infill20.gcode"));
    CHECK_THROWS_AS(elsewhere.plan(at.printed, 3, "", nullptr), std::runtime_error);
  }
  gcode::JoinStream unplanned(pair_path("cura_block_0.1_infill20.gcode"));
  std::string text;
  gcode::Precision precision;
  CHECK_THROWS_AS(unplanned.pump(text, gcode::SeamOptions{}, precision, nullptr), std::logic_error);
}
