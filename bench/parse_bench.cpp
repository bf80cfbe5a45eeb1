// Times the pieces of a full pass through libgcode, one stage per run, so
// bench/run.sh can set each against `cat` and see where the time goes:
//
//   split   LineReader only: block reads and line splitting
//   copy    split + OutputBuffer: every line written back from its raw bytes
//   parse   split + Line::parse
//   state   parse + MachineState::apply
//   layers  parse + state + LayerTracker, through the pipeline (a stage only counts)
//   full    layers + GcodeWriter: the pipeline every filter runs, with nothing to change
//
// Usage: parse_bench STAGE FILE
// The copy and full stages write to standard output; every stage prints one
// line of key=value figures to standard error, with a checksum of what it
// computed so the compiler cannot drop the work.
#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string_view>

#include "gcode/core/layer_marker.hpp"
#include "gcode/core/layer_tracker.hpp"
#include "gcode/core/line.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/core/output_buffer.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "gcode/pipeline/writer.hpp"

namespace {

struct Figures {
  std::uint64_t lines = 0;
  std::uint64_t bytes = 0;
  double check = 0;
};

Figures split(int in) {
  Figures f;
  gcode::LineReader reader(in);
  gcode::RawLine raw;
  while (reader.next(raw)) {
    ++f.lines;
    f.bytes += raw.size();
  }
  return f;
}

Figures copy(int in, int out) {
  Figures f;
  gcode::LineReader reader(in);
  gcode::OutputBuffer writer(out);
  gcode::RawLine raw;
  while (reader.next(raw)) {
    ++f.lines;
    writer.write(raw.text);
    writer.write(raw.ending);
  }
  writer.flush();
  f.bytes = writer.bytes_written();
  return f;
}

Figures parse(int in, bool with_state) {
  Figures f;
  gcode::LineReader reader(in);
  gcode::MachineState state;
  gcode::RawLine raw;
  std::uint64_t words = 0;
  while (reader.next(raw)) {
    ++f.lines;
    f.bytes += raw.size();
    gcode::Line line = gcode::Line::parse(raw.text);
    words += line.word_count();
    if (with_state) state.apply(line);
  }
  f.check = static_cast<double>(words) + state.filament_total;
  return f;
}

// Counts what reaches it; passes every line on.
class BenchStage : public gcode::Stage {
 public:
  void layer(const gcode::LayerInfo& layer, const gcode::MachineState& before, gcode::Emitter& out) override {
    z_sum += layer.z;
    out.layer(layer, before);
  }
  void line(const gcode::TrackedLine& t, gcode::Emitter& out) override {
    ++lines;
    bytes += t.raw.size();
    filament += t.move.filament;
    out.pass(t);
  }
  std::uint64_t lines = 0;
  std::uint64_t bytes = 0;
  double filament = 0;
  double z_sum = 0;
};

Figures layers(int in, int out, bool write) {
  gcode::OutputBuffer buffer(out);
  gcode::LayerMarkers markers;
  gcode::Pipeline pipeline(markers);
  BenchStage counter;
  gcode::GcodeWriter writer(buffer);
  pipeline.add(counter);
  if (write) pipeline.add(writer);
  pipeline.run(in);
  buffer.flush();
  Figures f;
  f.lines = counter.lines;
  f.bytes = counter.bytes;
  f.check = counter.filament + counter.z_sum + pipeline.tracker().layer_count();
  return f;
}

int usage() {
  std::fputs("usage: parse_bench split|copy|parse|state|layers|full FILE\n", stderr);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) return usage();
  std::string_view stage = argv[1];
  int in = ::open(argv[2], O_RDONLY);
  if (in < 0) {
    std::fprintf(stderr, "parse_bench: %s: %s\n", argv[2], std::strerror(errno));
    return 1;
  }
  const int out = 1;
  auto t0 = std::chrono::steady_clock::now();
  Figures f;
  if (stage == "split") {
    f = split(in);
  } else if (stage == "copy") {
    f = copy(in, out);
  } else if (stage == "parse") {
    f = parse(in, false);
  } else if (stage == "state") {
    f = parse(in, true);
  } else if (stage == "layers") {
    f = layers(in, out, false);
  } else if (stage == "full") {
    f = layers(in, out, true);
  } else {
    return usage();
  }
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  std::fprintf(stderr, "stage=%s lines=%llu bytes=%llu seconds=%.4f mb_per_s=%.1f maxrss_kb=%ld check=%.6g\n",
              argv[1], static_cast<unsigned long long>(f.lines), static_cast<unsigned long long>(f.bytes), seconds,
              static_cast<double>(f.bytes) / 1e6 / seconds, usage.ru_maxrss, f.check);
  return 0;
}
