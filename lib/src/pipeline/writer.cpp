#include "gcode/pipeline/writer.hpp"

namespace gcode {

void GcodeWriter::line(const TrackedLine& t, Emitter&) {
  ++lines_;
  if (open_line_) {
    out_.write(ending());
    open_line_ = false;
  }
  out_.write(t.raw.text);
  if (t.origin == LineOrigin::Inserted) {
    out_.write(ending());
    return;
  }
  const std::string_view end = t.raw.ending;
  out_.write(end);
  if (end.empty()) {
    open_line_ = true;
  } else if (t.origin == LineOrigin::Input && (end.size() != ending_size_ || end[0] != ending_[0])) {
    // Learned from the input's own lines ("\n" or "\r\n").
    ending_size_ = end.size() < 2 ? end.size() : 2;
    ending_[0] = end[0];
    ending_[1] = ending_size_ > 1 ? end[1] : 0;
  }
}

}  // namespace gcode
