#include "gcode/transform/layer_index.hpp"

#include <unistd.h>

#include <cerrno>
#include <system_error>

#include "gcode/core/e_mode.hpp"
#include "gcode/pipeline/pipeline.hpp"

namespace gcode {

namespace {
constexpr std::size_t kReadBlock = 1 << 18;
}  // namespace

// The stage of the index's own pipeline: it sees every line once.
class LayerIndex::Recorder : public Stage {
 public:
  explicit Recorder(LayerIndex& index) : index_(index), pipeline_(index.markers_) {
    pipeline_.add(*this);
    index_.settings_.emplace_back();
  }

  Pipeline& pipeline() { return pipeline_; }

  void layer(const LayerInfo& info, const MachineState& before, Emitter& out) override {
    close_layer(info.offset);
    IndexedLayer l;
    l.info = info;
    l.before = before;
    l.retracted = stream_.retracted;
    l.e_mode_set = stream_.e_mode_set;
    l.settings = static_cast<int>(index_.settings_.size()) - 1;
    index_.layers_.push_back(l);
    index_.open_ = true;
    out.layer(info, before);
  }

  void end_code(const EndCodeInfo& info, const MachineState& before, Emitter& out) override {
    // An empty end code has no offset: the last layer runs to the end.
    ended_ = true;
    end_offset_ = info.first_line != 0 ? info.offset : 0;
    if (info.first_line != 0) close_layer(info.offset);
    out.end_code(info, before);
  }

  void line(const TrackedLine& t, Emitter&) override {
    // A new version of the settings only when a value changes: layers share the rest.
    if (stream_.follow(t.line, t.move, t.before.tool) && !(stream_.settings == index_.settings_.back()))
      index_.settings_.push_back(stream_.settings);
    if (index_.open_) {
      IndexedLayer& l = index_.layers_.back();
      l.last_line = t.raw.number;
      if (t.move.extruding) {
        l.extent.add(t.move.start[kX], t.move.start[kY]);
        l.extent.add(t.move.end[kX], t.move.end[kY]);
      }
    }
  }

  void close_layer(std::uint64_t offset) {
    if (!index_.open_) return;
    index_.layers_.back().end = offset;
    index_.open_ = false;
  }

  bool ended() const { return ended_; }
  std::uint64_t end_offset() const { return end_offset_; }

 private:
  LayerIndex& index_;
  Pipeline pipeline_;
  StreamPoint stream_;  // retraction, settings (the newest version) and E mode; not its state
  bool ended_ = false;
  std::uint64_t end_offset_ = 0;
};

LayerIndex::LayerIndex(int fd, std::string name, const LayerMarkers& markers)
    : fd_(fd), name_(std::move(name)), markers_(markers) {
  // After every member: the recorder adds the first settings version.
  recorder_ = std::make_unique<Recorder>(*this);
  guess_e_mode_of_file();
}

void LayerIndex::guess_e_mode_of_file() {
  EModeReading reading = read_e_mode_of(fd_, EModeChoice::Auto, name_);
  if (reading.file_sets_mode) return;
  recorder_->pipeline().set_e_mode(reading.relative);
  e_mode_warning_ = reading.warning;
}

LayerIndex::~LayerIndex() = default;

const Precision& LayerIndex::precision() const { return recorder_->pipeline().precision(); }

bool LayerIndex::read_more() {
  if (complete_) return false;
  buffer_.resize(kReadBlock);
  ssize_t n;
  do {
    n = ::pread(fd_, buffer_.data(), buffer_.size(), static_cast<off_t>(read_));
  } while (n < 0 && errno == EINTR);
  if (n < 0) throw std::system_error(errno, std::generic_category(), "cannot read " + name_);
  if (n == 0) {
    recorder_->pipeline().finish();
    complete_ = true;
    // The end code's start, or the end of the file when there is none.
    end_code_offset_ = recorder_->end_offset() != 0 ? recorder_->end_offset() : read_;
    recorder_->close_layer(read_);
    return false;
  }
  read_ += static_cast<std::uint64_t>(n);
  recorder_->pipeline().feed(std::string_view(buffer_.data(), static_cast<std::size_t>(n)));
  return true;
}

bool LayerIndex::reach(int n) {
  while (layers() < n && read_more()) {
  }
  return layers() >= n;
}

void LayerIndex::reach_above(double z, int more) {
  for (;;) {
    int above = 0;
    for (int i = 1; i <= layers(); ++i)
      if (layer(i).info.z > z + 1e-9) {
        above = i;
        break;
      }
    if (above > 0 && layers() >= above + more) return;
    if (!read_more()) return;
  }
}

void LayerIndex::read_all() {
  while (read_more()) {
  }
}

StreamPoint LayerIndex::point(int n) const {
  const IndexedLayer& l = layer(n);
  StreamPoint p;
  p.state = l.before;
  p.retracted = l.retracted;
  p.settings = settings(l.settings);
  p.e_mode_set = l.e_mode_set;
  p.layer_z = l.info.z;
  return p;
}

Box2 LayerIndex::extent(int first, int last) const {
  Box2 box;
  for (int i = first; i <= last && i <= layers(); ++i)
    if (i >= 1) box.add(layer(i).extent);
  return box;
}

}  // namespace gcode
