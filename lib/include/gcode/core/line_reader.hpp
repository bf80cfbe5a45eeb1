#pragma once
// Splits a byte stream into lines without copying them one by one.
//
// Every line keeps its exact bytes and its own ending, so a tool that does not
// change a line writes back exactly what it read (LF, CRLF, a lone CR before LF
// inside binary junk, or no final newline at all).
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
};

class LineReader {
 public:
  // Reads from an open file descriptor; does not own or close it.
  explicit LineReader(int fd, std::size_t block_size = 1 << 18);

  // The next line, or false at the end of input. The views stay valid until
  // the next call. Lines of any length are returned whole.
  bool next(RawLine& line);

  std::uint64_t bytes_read() const { return consumed_; }

 private:
  bool refill();

  int fd_;
  std::size_t block_size_;
  std::vector<char> buffer_;
  std::size_t begin_ = 0;  // first unconsumed byte
  std::size_t end_ = 0;    // one past the last valid byte
  bool eof_ = false;
  std::uint64_t line_number_ = 0;
  std::uint64_t consumed_ = 0;
};

// Splits an in-memory buffer the same way (tests, fuzzing, small files).
class MemoryLineSplitter {
 public:
  explicit MemoryLineSplitter(std::string_view data) : data_(data) {}
  bool next(RawLine& line);

 private:
  std::string_view data_;
  std::size_t pos_ = 0;
  std::uint64_t line_number_ = 0;
};

}  // namespace gcode
