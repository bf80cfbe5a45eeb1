// The library's one loop (pipeline/pipeline.hpp): the same output whether
// the input comes as one text, byte by byte, from a pipe in tiny blocks, or
// after a header was read ahead; the input's precision per letter; layer
// events only when tracked; stages finished once, in order.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "gcode/core/output_buffer.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "gcode/pipeline/writer.hpp"
#include "fn_stage.hpp"
#include "test_support.hpp"

using gcode::Emitter;
using gcode::Pipeline;
using gcode::PipelineOptions;
using gcode::Stage;
using gcode::TrackedLine;

namespace {

const char* kText =
    ";FLAVOR:Marlin\r\nM83\r\nG28 ; home all axes, a comment longer than a tiny block of sixteen bytes\r\n"
    ";LAYER:0\r\n;TYPE:WALL-OUTER\r\nG1 Z0.2 F600\r\nG1 X10.125 Y10 E0.5 F1800\r\nG1 X20 Y10.5 E0.25\r\n"
    ";LAYER:1\r\nG1 Z0.4\r\nG1 X10 Y20 E0.5\r\nG1 E-0.8\r\nM84";

// Counts events and adds a line at each layer, so the output shows them.
class Marking : public Stage {
 public:
  void layer(const gcode::LayerInfo& info, const gcode::MachineState& before, Emitter& out) override {
    layers.push_back(info.index);
    out.insert("; layer " + std::to_string(info.index));
    out.layer(info, before);
  }
  void line(const TrackedLine& t, Emitter& out) override {
    ++lines;
    out.pass(t);
  }
  void finish(Emitter& out) override {
    ++finished;
    out.insert("; end");
  }
  std::vector<int> layers;
  int lines = 0, finished = 0;
};

const char* kMarked =
    ";FLAVOR:Marlin\r\nM83\r\nG28 ; home all axes, a comment longer than a tiny block of sixteen bytes\r\n"
    "; layer 1\r\n;LAYER:0\r\n;TYPE:WALL-OUTER\r\nG1 Z0.2 F600\r\nG1 X10.125 Y10 E0.5 F1800\r\nG1 X20 Y10.5 E0.25\r\n"
    "; layer 2\r\n;LAYER:1\r\nG1 Z0.4\r\nG1 X10 Y20 E0.5\r\nG1 E-0.8\r\nM84\r\n; end\r\n";

// Runs the text through a Marking stage and a writer, fed by `feed`.
template <typename Feed>
std::string marked(Feed feed, PipelineOptions options = {}) {
  gcode::LayerMarkers markers;
  Pipeline pipeline(markers, options);
  Marking marking;
  pipeline.add(marking);
  std::string out;
  {
    gcode::OutputBuffer buffer(out);
    gcode::GcodeWriter writer(buffer);
    pipeline.add(writer);
    feed(pipeline);
  }
  CHECK(marking.finished == 1);
  CHECK(marking.lines == 13);
  return out;
}

// A pipe with `text` written into it by a thread (the reader sees short reads).
struct Pipe {
  int fds[2];
  std::thread writer;
  explicit Pipe(std::string text) {
    REQUIRE(::pipe(fds) == 0);
    writer = std::thread([fd = fds[1], text = std::move(text)] {
      for (std::size_t at = 0; at < text.size(); at += 7) {
        std::size_t n = std::min<std::size_t>(7, text.size() - at);
        if (::write(fd, text.data() + at, n) != static_cast<ssize_t>(n)) break;
      }
      ::close(fd);
    });
  }
  ~Pipe() {
    writer.join();
    ::close(fds[0]);
  }
  int fd() const { return fds[0]; }
};

}  // namespace

TEST_CASE("pipeline: one text, byte by byte, or from a pipe: the same stream", "[pipeline]") {
  CHECK(marked([](Pipeline& p) { p.run_text(kText); }) == kMarked);
  CHECK(marked([](Pipeline& p) {
          std::string_view text = kText;
          for (char c : text) p.feed(std::string_view(&c, 1));
          p.finish();
          p.finish();  // once is enough
        }) == kMarked);
  CHECK(marked(
            [](Pipeline& p) {
              Pipe pipe(kText);
              p.run(pipe.fd());
              CHECK(p.finished());
              CHECK_FALSE(p.read_some(pipe.fd()));
            },
            PipelineOptions{.layers = true, .block_size = 16}) == kMarked);
}

TEST_CASE("pipeline: a header read ahead is processed first, nothing lost", "[pipeline]") {
  CHECK(marked(
            [](Pipeline& p) {
              Pipe pipe(kText);
              std::string_view header = p.read_header(pipe.fd());
              // Up to and including the first motion command (G28), maybe more.
              CHECK(header.substr(0, 27) == ";FLAVOR:Marlin\r\nM83\r\nG28 ; ");
              CHECK(header.find("G28") != std::string_view::npos);
              CHECK(p.buffered() == header);
              p.run(pipe.fd());
            },
            PipelineOptions{.layers = true, .block_size = 16}) == kMarked);
  CHECK(marked(
            [](Pipeline& p) {
              Pipe pipe(kText);
              std::string_view ahead = p.read_ahead(pipe.fd(), 40);
              CHECK(ahead.size() >= 40);
              CHECK(ahead == std::string_view(kText).substr(0, ahead.size()));
              p.run(pipe.fd());
            },
            PipelineOptions{.layers = true, .block_size = 16}) == kMarked);
  // Asking for more than there is: everything, and the end noticed.
  CHECK(marked([](Pipeline& p) {
          Pipe pipe(kText);
          CHECK(p.read_ahead(pipe.fd(), 1 << 20) == kText);
          CHECK(p.read_header(pipe.fd()) == kText);
          p.run(pipe.fd());
        }) == kMarked);
}

TEST_CASE("pipeline: a header with no motion command is read up to the limit", "[pipeline]") {
  gcode::LayerMarkers markers;
  Pipeline p(markers, PipelineOptions{.layers = true, .block_size = 16});
  std::string text;
  for (int i = 0; i < 50; ++i) text += "; comment line " + std::to_string(i) + "\n";
  Pipe pipe(text + "G1 X1\n");
  std::string_view header = p.read_header(pipe.fd(), 100);
  CHECK(header.size() >= 100);
  CHECK(header.find("G1") == std::string_view::npos);
  CHECK(text.substr(0, header.size()) == header);
  p.finish();
}

TEST_CASE("pipeline: the input's decimals per letter, never fewer than the usual", "[pipeline]") {
  gcode::LayerMarkers markers;
  Pipeline p(markers);
  p.run_text("G1 X10.1255 Y2.5 Z0.2 F1800.5\nG1 X1.25 E0.123456\nG1 Z0.123456789012\n");
  CHECK(p.precision().of('X') == 4);
  CHECK(p.precision().of('Y') == 3);  // X/Y/Z 3, E 5, F 0 at least
  CHECK(p.precision().of('Z') == 9);  // at most nine
  CHECK(p.precision().of('E') == 6);
  CHECK(p.precision().of('F') == 1);
  Pipeline q(markers);
  q.run_text(kText);
  CHECK(q.precision().of('X') == 3);
  CHECK(q.precision().of('E') == 5);
  CHECK(q.precision().of('F') == 0);
  CHECK(q.tracker().layer_count() == 2);
  CHECK(q.feature_name(0) == "WALL-OUTER");
}

TEST_CASE("pipeline: without layer tracking there are no layer events", "[pipeline]") {
  gcode::LayerMarkers markers;
  Pipeline p(markers, PipelineOptions{.layers = false});
  Marking marking;
  p.add(marking);
  p.run_text(kText);
  CHECK(marking.layers.empty());
  CHECK(marking.lines == 13);
}

TEST_CASE("pipeline: stages are added before the first line only", "[pipeline]") {
  gcode::LayerMarkers markers;
  Pipeline p(markers);
  Marking a, b;
  p.add(a);
  p.feed("G28\n");
  CHECK_THROWS_AS(p.add(b), std::logic_error);
  p.finish();
  CHECK(a.finished == 1);
}

TEST_CASE("pipeline: each stage finishes once, its last lines go through the later stages", "[pipeline]") {
  gcode::LayerMarkers markers;
  Pipeline p(markers);
  Marking first, second;
  p.add(first);
  p.add(second);
  std::string out = gctest::run_stages(p, "G28\n");
  CHECK(out == "G28\n; end\n; end\n");
  CHECK(first.finished == 1);
  CHECK(second.finished == 1);
  CHECK(second.lines == 2);  // the input line and the first stage's "; end"
}

TEST_CASE("pipeline: finishing early leaves a line the last read cut off unread", "[pipeline]") {
  gcode::LayerMarkers markers;
  Pipeline p(markers, PipelineOptions{.layers = false});
  Marking marking;
  p.add(marking);
  std::string out;
  {
    gcode::OutputBuffer buffer(out);
    gcode::GcodeWriter writer(buffer);
    p.add(writer);
    p.feed("G1 X1\nG1 X2\nG1 X4");  // "G1 X45..." still on its way
    p.finish_early();
    p.finish_early();
    p.finish();  // finished already: nothing more
  }
  CHECK(out == "G1 X1\nG1 X2\n; end\n");
  CHECK(marking.lines == 2);
  CHECK(marking.finished == 1);
  CHECK(p.finished());
}

TEST_CASE("pipeline: a stream that continues another starts from its state", "[pipeline]") {
  gcode::MachineState s;
  s.set(gcode::kX, gcode::Fixed::from_double(10));
  s.set(gcode::kY, gcode::Fixed::from_double(20));
  s.set(gcode::kE, gcode::Fixed::from_double(5));
  s.relative_xyz = true;
  s.relative_e = true;
  gcode::LayerMarkers markers;
  Pipeline p(markers);
  std::vector<double> xs, es;
  gctest::FnStage stage([&](const gcode::TrackedLine& t, gcode::Emitter& out) {
    xs.push_back(t.state.at(gcode::kX).to_double());
    es.push_back(t.move.filament);
    out.pass(t);
  });
  p.add(stage);
  p.start_from(s);
  p.run_text("G1 X5 E0.5\nG90\nG1 X1\n");
  // Relative moves from X 10; G90 makes both absolute (Marlin), as the state says.
  REQUIRE(xs.size() == 3);
  CHECK(xs[0] == Approx(15));
  CHECK(es[0] == Approx(0.5));
  CHECK(xs[2] == Approx(1));
  CHECK(p.tracker().state().at(gcode::kY).to_double() == Approx(20));
}
