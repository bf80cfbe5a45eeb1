// libFuzzer target: the whole streaming pipeline on arbitrary bytes.
//
//   reader -> Line -> MachineState -> LayerTracker -> writer
//   bytes pushed in random pieces -> LineSplitter -> Pipeline -> GcodeWriter
//
// The input goes through LineReader (from a memfd, with a small block size
// picked by the first byte so lines straddle and outgrow the buffer), every
// line is parsed and tracked, and the sink writes every line back through an
// OutputBuffer with a small capacity. The result must be the input, byte for
// byte, and the lines must arrive once each, in order, with consistent
// numbers and offsets; anything else aborts, which libFuzzer reports as a
// crash. The same bytes are then pushed in pieces of random sizes through
// the library's Pipeline (gc-send's way in) into the GcodeWriter: the output
// must again be the input. Every line is also parsed by the previous parser
// (tests/support/reference_line.cpp), which must agree field by field. The
// sanitizers (ASan, UBSan) catch the rest.
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <algorithm>
#include <cstdlib>
#include <string>
#include <string_view>

#include "gcode/core/layer_marker.hpp"
#include "gcode/core/layer_tracker.hpp"
#include "gcode/core/line.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/core/number.hpp"
#include "gcode/core/output_buffer.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "gcode/pipeline/writer.hpp"
#include "reference_line.hpp"

namespace {

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "fuzz_pipeline: %s\n", what);
  std::abort();
}

void check(bool ok, const char* what) {
  if (!ok) fail(what);
}

// An anonymous in-memory file holding `data` (or nothing), positioned at 0.
int memory_file(std::string_view data) {
  int fd = ::memfd_create("gcode-fuzz", 0);
  check(fd >= 0, "memfd_create failed");
  std::size_t done = 0;
  while (done < data.size()) {
    ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    check(n > 0, "write to memfd failed");
    done += static_cast<std::size_t>(n);
  }
  check(::lseek(fd, 0, SEEK_SET) == 0, "lseek failed");
  return fd;
}

std::string read_all(int fd) {
  std::string out;
  check(::lseek(fd, 0, SEEK_SET) == 0, "lseek failed");
  char buffer[1 << 16];
  for (;;) {
    ssize_t n = ::read(fd, buffer, sizeof buffer);
    check(n >= 0, "read from memfd failed");
    if (n == 0) break;
    out.append(buffer, static_cast<std::size_t>(n));
  }
  return out;
}

class EchoSink : public gcode::LayerSink {
 public:
  explicit EchoSink(gcode::OutputBuffer& out) : out_(out) {}

  void on_layer(const gcode::LayerInfo& layer, const gcode::MachineState&) override {
    check(layer.index == last_layer_ + 1, "layers not numbered 1, 2, 3 ...");
    last_layer_ = layer.index;
  }
  void on_end_code(std::uint64_t, std::uint64_t, const gcode::MachineState&) override {
    check(!saw_end_, "end code announced twice");
    saw_end_ = true;
  }
  void on_line(const gcode::TrackedLine& t) override {
    check(t.raw.number == lines + 1, "line numbers out of order");
    check(t.raw.offset == bytes, "line offsets out of order");
    check(t.line.text.data() == t.raw.text.data() || t.line.text == t.raw.text, "Line does not view its text");
    check(t.line.word_count() <= gcode::Line::kMaxWords, "too many words");
    check(t.layer <= last_layer_, "line in a layer not announced");
    check(t.region != gcode::Region::EndCode || saw_end_, "end code line before on_end_code");
    // Exercise the accessors on every line.
    for (const gcode::Word& w : t.line) {
      check(w.letter >= 'A' && w.letter <= 'Z', "word letter not upper case");
      // Line reads numbers in its own fast pass; it must agree with
      // parse_number bit for bit.
      double v = 0;
      if (w.has_value) check(gcode::parse_number(w.raw, v) && v == w.value(), "word value differs from parse_number");
    }
    (void)t.line.comment_text();
    (void)t.line.code();
    check(gctest::compare_with_reference(t.line, gctest::reference_parse(t.raw.text)).empty(),
          "Line::parse differs from the reference parser");
    ++lines;
    bytes += t.raw.size();
    out_.write(t.raw.text);
    out_.write(t.raw.ending);
  }

  std::uint64_t lines = 0;
  std::uint64_t bytes = 0;

 private:
  gcode::OutputBuffer& out_;
  int last_layer_ = 0;
  bool saw_end_ = false;
};

// The same split from memory must give the same lines as the reader did.
std::uint64_t count_memory_lines(std::string_view data) {
  gcode::MemoryLineSplitter split(data);
  gcode::RawLine raw;
  std::uint64_t n = 0, bytes = 0;
  while (split.next(raw)) {
    check(raw.offset == bytes, "MemoryLineSplitter offsets out of order");
    check(std::string_view(data.data() + raw.offset, raw.size()) ==
              std::string(raw.text) + std::string(raw.ending),
          "MemoryLineSplitter line is not the input's bytes");
    bytes += raw.size();
    ++n;
  }
  check(bytes == data.size(), "MemoryLineSplitter lost bytes");
  return n;
}

// A stage that checks order and continuity, and passes everything on.
class OrderCheck : public gcode::Stage {
 public:
  void line(const gcode::TrackedLine& t, gcode::Emitter& out) override {
    check(t.raw.number == lines + 1, "pipeline: line numbers out of order");
    check(t.raw.offset == bytes, "pipeline: line offsets out of order");
    ++lines;
    bytes += t.raw.size();
    out.pass(t);
  }
  std::uint64_t lines = 0;
  std::uint64_t bytes = 0;
};

// Pushes `input` in pieces of 1..`max_piece` bytes through a Pipeline.
std::string through_pipeline(std::string_view input, const gcode::LayerMarkers& markers, std::size_t max_piece,
                             std::uint64_t& lines) {
  std::string out;
  {
    gcode::OutputBuffer buffer(out, 64);
    gcode::Pipeline pipeline(markers, gcode::PipelineOptions{.layers = true, .block_size = 16});
    OrderCheck order;
    gcode::GcodeWriter writer(buffer);
    pipeline.add(order);
    pipeline.add(writer);
    std::size_t pos = 0, step = 0;
    while (pos < input.size()) {
      std::size_t piece = 1 + (step++ * 7919 + input.size()) % max_piece;
      piece = std::min(piece, input.size() - pos);
      pipeline.feed(input.substr(pos, piece));
      pos += piece;
    }
    pipeline.finish();
    lines = order.lines;
  }
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view input(reinterpret_cast<const char*>(data), size);
  // Small blocks and buffers so that refills, growth and flushes happen often.
  std::size_t block = size > 0 ? 1 + data[0] % 64 : 16;
  std::size_t capacity = size > 1 ? 1 + data[1] % 128 : 16;
  // A user marker pattern on some inputs, to cover that path too.
  static const gcode::LayerMarkers builtin;
  static const gcode::LayerMarkers user(R"(^\s*layer\s+(\d+))");
  const gcode::LayerMarkers& markers = size > 2 && data[2] % 4 == 0 ? user : builtin;

  int in = memory_file(input);
  int out = memory_file({});
  std::uint64_t lines = 0, bytes = 0;
  {
    gcode::OutputBuffer writer(out, capacity);
    EchoSink sink(writer);
    gcode::LayerTracker tracker(sink, markers);
    gcode::LineReader reader(in, block);
    gcode::RawLine raw;
    while (reader.next(raw)) tracker.push(raw);
    tracker.finish();
    writer.flush();
    check(reader.bytes_read() == size, "reader did not consume every byte");
    check(writer.bytes_written() == size, "writer byte count differs from the input");
    lines = sink.lines;
    bytes = sink.bytes;
  }
  check(bytes == size, "the sink did not see every byte");
  check(read_all(out) == input, "writing every line back is not byte-identical to the input");
  check(count_memory_lines(input) == lines, "MemoryLineSplitter and LineReader disagree on the line count");
  std::uint64_t pushed_lines = 0;
  check(through_pipeline(input, markers, size > 3 ? 1 + data[3] % 97 : 5, pushed_lines) == input,
        "the pipeline fed in pieces is not byte-identical to the input");
  check(pushed_lines == lines, "the pipeline and LineReader disagree on the line count");
  ::close(in);
  ::close(out);
  return 0;
}
