#pragma once
// The output conventions, in one place: the last stage of every filter.
//
//   - a line no stage changed is written from its raw bytes (spacing,
//     comments, case, CRLF, a missing final newline: byte for byte);
//   - a line a stage changed keeps the input line's own ending;
//   - a line a stage added gets the input's line ending (CRLF in, CRLF out);
//     the writer owns that ending (a copy), never a view into a buffer that
//     the reader may have refilled since; lines added before the first input
//     line wait for it to show the ending (a file that is all added lines
//     gets "\n");
//   - after an input line without a final newline, a line that follows gets
//     the ending it needs first;
//   - a closed pipe ends the tool quietly (OutputBuffer's BrokenPipe).
// Numbers in changed and added lines are the stages' to format at the
// input's precision (Pipeline::precision, line_edit.hpp).
#include <cstdint>
#include <string>

#include "gcode/core/output_buffer.hpp"
#include "gcode/pipeline/stage.hpp"

namespace gcode {

class GcodeWriter : public Stage {
 public:
  explicit GcodeWriter(OutputBuffer& out) : out_(out) {}

  void line(const TrackedLine& t, Emitter& out) override;
  // Writes lines still held for the first input line's ending.
  void finish(Emitter& out) override;
  bool reads_state() const override { return false; }
  bool reads_lines() const override { return false; }

  // The line ending added lines get: the input's, "\n" until one was seen.
  std::string_view ending() const { return {ending_, ending_size_}; }
  std::uint64_t lines_written() const { return lines_; }

 private:
  OutputBuffer& out_;
  char ending_[2] = {'\n', 0};
  std::size_t ending_size_ = 1;
  bool open_line_ = false;  // the last line written had no ending
  bool seen_input_ = false;  // an input line (or a changed one) was written
  std::string held_;         // added lines before it, each ended by '\n'
  void learn(std::string_view ending);
  void write_held();
  std::uint64_t lines_ = 0;
};

}  // namespace gcode
