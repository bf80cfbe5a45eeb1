#pragma once
// Splits a byte stream into lines without copying them one by one.
//
// Every line keeps its exact bytes and its own ending, so a tool that does not
// change a line writes back exactly what it read (LF, CRLF, a lone CR before LF
// inside binary junk, or no final newline at all).
//
// LineSplitter is the one splitter of the library. It is push-style: bytes go
// in as they arrive (read straight into its buffer, or appended), complete
// lines come out. A file is read by filling it block by block (LineReader);
// gc-send feeds it whatever its event loop read from a pipe. Lines are handed
// out as views into the buffer, valid until more bytes go in.
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

namespace gcode {

struct RawLine {
  std::string_view text;    // the line without its ending
  std::string_view ending;  // "\n", "\r\n" or "" (last line with no newline)
  std::uint64_t number = 0; // 1-based line number in the input
  std::uint64_t offset = 0; // byte offset of the first byte of the line

  std::size_t size() const { return text.size() + ending.size(); }
  // The text and its ending as one view, when the ending follows the text
  // in memory (as read; "" otherwise): one copy for both.
  std::string_view whole() const {
    return text.data() + text.size() == ending.data() ? std::string_view(text.data(), size()) : std::string_view();
  }
};

class LineSplitter {
 public:
  explicit LineSplitter(std::size_t block_size = 1 << 18);

  // Room for at least one block of input at the end of the buffer; write
  // into it, then commit() how many bytes were written. Invalidates the
  // views of lines handed out before.
  char* room();
  std::size_t room_size() const { return buffer_.size() - end_; }
  void commit(std::size_t bytes) { end_ += bytes; }
  // Copies bytes in (gc-send's reads). Invalidates earlier views.
  void append(std::string_view bytes);
  // No more input: a last line without a newline becomes a line.
  void end_of_input() { ended_ = true; }

  // The next complete line, or false until more bytes (or the end) come.
  // Lines of any length come out whole.
  bool next(RawLine& line);

  bool ended() const { return ended_; }
  // Bytes received and not yet handed out as lines.
  std::string_view pending() const { return {buffer_.data() + begin_, end_ - begin_}; }
  std::uint64_t lines() const { return line_number_; }
  std::uint64_t bytes_received() const { return consumed_ + (end_ - begin_); }

 private:
  void make_room(std::size_t bytes);

  std::size_t block_size_;
  std::vector<char> buffer_;
  std::size_t begin_ = 0;    // first byte not yet handed out
  std::size_t end_ = 0;      // one past the last byte received
  std::size_t scanned_ = 0;  // bytes after begin_ known to hold no newline
  bool ended_ = false;
  std::uint64_t line_number_ = 0;
  std::uint64_t consumed_ = 0;  // bytes handed out as lines
};

// Reads a file descriptor to its end through a LineSplitter (pull style).
class LineReader {
 public:
  // Does not own or close the descriptor.
  explicit LineReader(int fd, std::size_t block_size = 1 << 18);

  // The next line, or false at the end of input. The views stay valid until
  // the next call.
  bool next(RawLine& line);
  // Reads one block into the splitter; false at the end of input.
  bool fill();
  LineSplitter& splitter() { return splitter_; }
  std::uint64_t bytes_read() const { return splitter_.bytes_received(); }

 private:
  int fd_;
  LineSplitter splitter_;
};

// Splits an in-memory buffer the same way (tests, fuzzing, small texts),
// without copying it.
class MemoryLineSplitter {
 public:
  explicit MemoryLineSplitter(std::string_view data) : data_(data) {}
  bool next(RawLine& line);

 private:
  std::string_view data_;
  std::size_t pos_ = 0;
  std::uint64_t line_number_ = 0;
};

// Reads up to `bytes` from `fd` into `out` (EINTR retried); returns the count,
// 0 at the end of input. Throws std::system_error on a read error.
std::size_t read_some(int fd, char* out, std::size_t bytes);

}  // namespace gcode
