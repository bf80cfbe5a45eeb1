#include "gcode/pipeline/writer.hpp"

namespace gcode {

void GcodeWriter::line(const TrackedLine& t, Emitter&) {
  if (!seen_input_) {
    if (t.origin == LineOrigin::Inserted) {
      // Before the first input line the file's ending is not known yet.
      held_.append(t.raw.text);
      held_.push_back('\n');
      return;
    }
    seen_input_ = true;
    if (!t.raw.ending.empty()) learn(t.raw.ending);
    write_held();
  }
  ++lines_;
  if (open_line_) {
    out_.write(ending());
    open_line_ = false;
  }
  const std::string_view end = t.raw.ending;
  if (t.origin == LineOrigin::Inserted) {
    out_.write(t.raw.text);
    out_.write(ending());
    return;
  }
  // An input line's ending follows its text in the buffer it was read into:
  // one copy for both (a call and a branch fewer a line: callgrind).
  if (const std::string_view whole = t.raw.whole(); !whole.empty()) {
    out_.write(whole);
  } else {
    out_.write(t.raw.text);
    out_.write(end);
  }
  if (end.empty()) {
    open_line_ = true;
  } else if (t.origin == LineOrigin::Input && (end.size() != ending_size_ || end[0] != ending_[0])) {
    learn(end);
  }
}

// Learned from the input's own lines ("\n" or "\r\n").
void GcodeWriter::learn(std::string_view end) {
  ending_size_ = end.size() < 2 ? end.size() : 2;
  ending_[0] = end[0];
  ending_[1] = ending_size_ > 1 ? end[1] : 0;
}

void GcodeWriter::write_held() {
  std::string_view held = held_;
  while (!held.empty()) {
    std::size_t nl = held.find('\n');
    ++lines_;
    out_.write(held.substr(0, nl));
    out_.write(ending());
    held.remove_prefix(nl + 1);
  }
  held_.clear();
}

void GcodeWriter::finish(Emitter&) {
  seen_input_ = true;
  write_held();
}

}  // namespace gcode
