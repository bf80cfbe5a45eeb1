#pragma once
// Another file that continues a print while it runs (gc-send's `swap FILE`),
// as text to be fed on: gc-relayer's join (relayer.hpp: layers already
// covered left out, the missing height filled, the new file's start code left
// out but its settings carried, its end code kept) from wherever the print
// stands, read a piece at a time so a sender can pace it.
//
//   JoinStream next(path);              // opens and checks the file
//   next.plan(printed);                 // where it joins (again, if it moved on)
//   while (next.pump(text)) feed(text); // the seam, then the file's lines
//
// The text is exactly what `gc-relayer` writes after its join: the seam from
// `printed` (the printer as it stands: state, retraction, settings, top Z),
// then the blocks. Memory stays flat: one read of the file at a time.
#include <memory>
#include <string>
#include <vector>

#include "gcode/core/diagnostics.hpp"
#include "gcode/core/layer_marker.hpp"
#include "gcode/core/line_builder.hpp"
#include "gcode/transform/layer_index.hpp"
#include "gcode/transform/relayer.hpp"
#include "gcode/transform/seam.hpp"
#include "gcode/transform/splice.hpp"

namespace gcode {

class JoinStream {
 public:
  // Opens `path` (a regular file: it is read by layer; its layers are found
  // by the slicers' markers). Throws std::runtime_error with the reason when
  // it cannot be read.
  explicit JoinStream(const std::string& path);
  ~JoinStream();
  JoinStream(const JoinStream&) = delete;
  JoinStream& operator=(const JoinStream&) = delete;

  // Chooses the join onto a print that stands at `printed` (its top_z is
  // the printed height, its extent where it lies). `onto` names it for the
  // seam's comment. Throws std::runtime_error when the file has no layer
  // above or lies elsewhere; `diag` (may be null) hears of a seam that may
  // show. May be called again until the first pump().
  void plan(const StreamPoint& printed, int z_decimals, const std::string& onto, Diagnostics* diag);
  // Appends the next piece (the seam, then one read of the blocks' lines,
  // each line ending in '\n') to `text`; false once everything is out.
  bool pump(std::string& text, const SeamOptions& options, const Precision& precision, Diagnostics* diag);

  const std::string& path() const { return path_; }
  const Join& join() const { return blocks_.join; }
  // What the join prints, for the user.
  const std::vector<std::string>& report() const { return blocks_.report; }
  // The printer once the text so far has run (updated by pump()).
  const StreamPoint& printed() const { return printed_; }
  // The file's bytes from the join's first layer to its end, and how many
  // of them are out: for the progress.
  std::uint64_t bytes() const;
  std::uint64_t bytes_out() const { return bytes_out_; }
  const LayerMarkers& markers() const { return markers_; }

 private:
  struct TextSink;

  std::string path_;
  int fd_ = -1;
  LayerMarkers markers_;
  std::unique_ptr<LayerIndex> index_;
  JoinBlocks blocks_;
  bool planned_ = false;
  StreamPoint printed_;
  std::size_t next_block_ = 0;
  std::unique_ptr<BlockStream> stream_;
  std::uint64_t bytes_out_ = 0;
};

}  // namespace gcode
