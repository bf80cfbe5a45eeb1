#pragma once
// One run of a filter tool: the input (FILE or standard input), the
// pipeline with the tool's stages, the writer, and the output (standard
// output, -o FILE, or -i: FILE replaced atomically, only on success).
//
//   cli::Filter run(options);                 // opens the input
//   LayerSelection sel = run.selection(text); // counts layers first if "-3" asks
//   Subdivider stage(split, run.pipeline().precision(), &diag, &sel);
//   run.add(stage);
//   run.write();                              // writer, output, run, commit
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/file_io.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/core/output_buffer.hpp"
#include "gcode/core/print_area.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "gcode/pipeline/writer.hpp"

namespace gcode::cli {

// What one reading of a whole input finds before the real run.
struct InputScan {
  std::vector<LayerInfo> layers;      // every layer, in order (index 1, 2, ...)
  std::vector<std::string> features;  // the ;TYPE: names, in order of first appearance
};

class Filter {
 public:
  explicit Filter(const FilterOptions& options, PipelineOptions pipeline = {});
  Filter(const Filter&) = delete;
  Filter& operator=(const Filter&) = delete;

  InputFile& input() { return input_; }
  Pipeline& pipeline() { return pipeline_; }
  const LayerMarkers& markers() const { return markers_; }

  // The layers in the input: reads it once (a pipe is kept in a temp file
  // first) and goes back to its start.
  int count_layers();
  // Every layer (number, Z, height) and every ;TYPE: name of the input, for
  // a tool that must know them before its first byte goes out (a ramp across
  // the chosen layers, a check of --types): reads the input once, as
  // count_layers does, and goes back to its start. Read once: later calls
  // give the same scan.
  const InputScan& scan();
  // Reads the whole input once through `stage` (a pipeline of its own,
  // the same markers and E mode), then goes back to its start: for a tool
  // that must know the whole file (its objects) before the real run;
  // `after` sees that pipeline once it ran (its tracker: features, layers).
  void prepass(Stage& stage, const std::function<void(const Pipeline&)>& after = {});
  // Parses a selection and, when a range counts from the end, counts the
  // layers first; with --types, reads the file's features first and throws
  // UsageError for a name it does not have (before any output). Throws
  // UsageError when it does not parse.
  LayerSelection selection(const SelectionText& text);
  // After the run, what a selection found: --layers/--z-range that chose no
  // layer is a warning ("no layer of FILE matches the selection; nothing was
  // <done>"). (--types names the file lacks were refused by selection().)
  void check_selection(const LayerSelection& where, Diagnostics& diag, std::string_view done);
  // What the slicer's SLIC3R_* environment (a post-processing hook) and then
  // the file say about the printer (bed, height, the print's box, filament,
  // retraction): a regular file is read at both ends (PrusaSlicer writes its
  // config last); from a pipe only the header, which stays buffered for the run.
  PrintArea print_area();

  // The E mode of a file that never says M82/M83 (--e-mode, else guessed
  // from the file with one warning); applied to every pass over the input.
  // Returns whether E is read as relative where the file does not say.
  bool e_mode();

  void add(Stage& stage) { pipeline_.add(stage); }
  // Reads the input only until `done` says the tool needs no more of it
  // (gc-relayer once the new file has taken over); the rest is not read.
  void stop_when(std::function<bool()> done) { done_ = std::move(done); }
  // Opens the output, adds the writer after the tool's stages and runs the
  // whole input through; then `verify` (if given) checks what the run found
  // and may throw. The output is committed (-i: renamed over FILE) only if
  // everything succeeded.
  void write(const std::function<void()>& verify = {});
  // Runs the stages without any G-code output (reports).
  void run();
  // The writer's output, once write() opened it (for counts in messages).
  const OutputBuffer* output() const { return buffer_ ? &*buffer_ : nullptr; }

 private:
  const FilterOptions& options_;
  LayerMarkers markers_;
  int e_relative_ = -1;  // -1 not decided yet, else 0/1 (2: the file sets it)
  InputFile input_;
  Pipeline pipeline_;
  std::optional<OutputFile> file_;
  std::optional<OutputBuffer> buffer_;
  std::optional<GcodeWriter> writer_;
  std::function<bool()> done_;
  std::optional<InputScan> scanned_;
};

// --types names (`wanted`) that match none of a file's ;TYPE: names
// (`features`): a UsageError naming them and listing the file's names.
void check_types(const std::vector<std::string>& wanted, const std::vector<std::string>& features);

// A file a tool writes besides its G-code, or as its only output (layer
// pictures, a lithophane's G-code and STL): `path` "" or "-" is standard
// output; `fill` writes through the buffer, which is flushed and the file
// closed once `fill` returned.
void write_output_file(const std::string& path, const std::function<void(OutputBuffer&)>& fill);

// Counts the layers of everything `fd` delivers (no output); `e_relative`:
// 1 or 0 for a file that never sets the E mode, -1 to leave it to the file.
int count_layers(int fd, const LayerMarkers& markers, int e_relative = -1);

}  // namespace gcode::cli
