#pragma once
// Random access into a G-code file by layer: one pass records where each
// layer lies (its byte range, as `gc-layers --where` reports it) and how the
// machine stands at its first byte (state, retraction, carried settings), so
// a splice can seek to any layer and stream it (splice.hpp) without reading
// what comes before it again.
//
// The pass is lazy: it reads only as far as asked (reach(), reach_above()),
// so joining a re-sliced file at 12 mm reads its first 12 mm once and the
// rest only while it is printed. It reads with pread and never moves the
// descriptor's offset, so the file a pipeline is reading can be indexed too.
// Memory grows with the number of layers (a few hundred bytes each), never
// with the file's size.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "gcode/core/geometry.hpp"
#include "gcode/core/layer_marker.hpp"
#include "gcode/core/layer_tracker.hpp"
#include "gcode/core/line_builder.hpp"
#include "gcode/transform/stream_tracker.hpp"

namespace gcode {

struct IndexedLayer {
  LayerInfo info;             // index, z, height, first_line, offset (its first byte)
  std::uint64_t end = 0;      // one past its last byte
  std::uint64_t last_line = 0;
  MachineState before;        // the state at its first byte
  double retracted = 0;       // E retraction in effect there
  bool e_mode_set = false;    // an M82/M83 came before it
  int settings = 0;           // which version of the carried settings is in effect (LayerIndex::settings)
  Box2 extent;                // XY extent of its extrusions
};

class LayerIndex {
 public:
  // `fd` is a regular file (or anything pread works on); not owned.
  // `name` is for messages; `markers` must outlive the index. A file that
  // never sets its E mode (M82/M83) is read in the mode guessed from its
  // extrusions and config, as a tool reads its input (--e-mode auto).
  LayerIndex(int fd, std::string name, const LayerMarkers& markers);
  ~LayerIndex();
  LayerIndex(const LayerIndex&) = delete;
  LayerIndex& operator=(const LayerIndex&) = delete;

  // Reads on until layer `n` is complete (its end known) or the file ends;
  // returns whether the file has that many layers.
  bool reach(int n);
  // Reads on until the first layer above `z` and `more` layers after it are
  // complete, or the file ends.
  void reach_above(double z, int more = 1);
  void read_all();

  bool complete() const { return complete_; }
  // Complete layers so far (all of them once complete()).
  int layers() const { return static_cast<int>(layers_.size()) - (open_ ? 1 : 0); }
  const IndexedLayer& layer(int n) const { return layers_.at(static_cast<std::size_t>(n - 1)); }
  // How the stream stands at layer n's first byte (layer_z = its Z).
  StreamPoint point(int n) const;
  const CarriedSettings& settings(int version) const { return settings_.at(static_cast<std::size_t>(version)); }
  // XY extent of the extrusions of layers first..last.
  Box2 extent(int first, int last) const;

  // Valid once complete(): where the end code starts (the file's size when
  // it is empty) and the state there.
  std::uint64_t end_code_offset() const { return end_code_offset_; }
  std::uint64_t size() const { return read_; }

  // The decimals the file uses per letter, as far as read.
  const Precision& precision() const;
  int fd() const { return fd_; }
  const std::string& name() const { return name_; }
  const LayerMarkers& markers() const { return markers_; }
  // Set when the E mode was guessed: what was chosen and why, for a warning.
  const std::string& e_mode_warning() const { return e_mode_warning_; }

 private:
  class Recorder;
  bool read_more();
  void guess_e_mode_of_file();

  int fd_;
  std::string name_;
  const LayerMarkers& markers_;
  std::unique_ptr<Recorder> recorder_;
  std::vector<IndexedLayer> layers_;
  std::vector<CarriedSettings> settings_;
  bool open_ = false;          // the last layer's end is not known yet
  bool complete_ = false;
  std::uint64_t read_ = 0;     // bytes read
  std::uint64_t end_code_offset_ = 0;
  std::vector<char> buffer_;
  std::string e_mode_warning_;
};

}  // namespace gcode
