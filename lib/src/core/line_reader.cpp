#include "gcode/core/line_reader.hpp"

#include <cerrno>
#include <cstring>
#include <system_error>
#include <unistd.h>

namespace gcode {

namespace {

// Fills `line` from data[start, nl) where nl is the index of '\n' or npos.
void split_at(std::string_view data, std::size_t start, std::size_t nl, RawLine& line) {
  if (nl == std::string_view::npos) {
    line.text = data.substr(start);
    line.ending = {};
    return;
  }
  std::size_t text_end = nl;
  if (text_end > start && data[text_end - 1] == '\r') --text_end;
  line.text = data.substr(start, text_end - start);
  line.ending = data.substr(text_end, nl + 1 - text_end);
}

}  // namespace

LineReader::LineReader(int fd, std::size_t block_size)
    : fd_(fd), block_size_(block_size), buffer_(block_size * 2) {}

bool LineReader::refill() {
  // Move the unfinished line to the front, grow if a single line fills the buffer.
  if (begin_ > 0) {
    std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
    end_ -= begin_;
    begin_ = 0;
  }
  if (buffer_.size() - end_ < block_size_) buffer_.resize(buffer_.size() * 2);
  for (;;) {
    ssize_t n = ::read(fd_, buffer_.data() + end_, buffer_.size() - end_);
    if (n > 0) {
      end_ += static_cast<std::size_t>(n);
      return true;
    }
    if (n == 0) {
      eof_ = true;
      return false;
    }
    if (errno == EINTR) continue;
    throw std::system_error(errno, std::generic_category(), "read");
  }
}

bool LineReader::next(RawLine& line) {
  std::size_t scan_from = begin_;
  for (;;) {
    const char* base = buffer_.data();
    const void* hit = std::memchr(base + scan_from, '\n', end_ - scan_from);
    if (hit != nullptr) {
      std::size_t nl = static_cast<const char*>(hit) - base;
      std::string_view data(base, end_);
      split_at(data, begin_, nl, line);
      break;
    }
    if (eof_ || (scan_from = end_ - begin_, !refill())) {
      if (begin_ == end_) return false;
      std::string_view data(buffer_.data(), end_);
      split_at(data, begin_, std::string_view::npos, line);
      break;
    }
    // refill() moved the pending bytes to the front: continue where we stopped.
  }
  line.number = ++line_number_;
  line.offset = consumed_;
  consumed_ += line.size();
  begin_ += line.size();
  return true;
}

bool MemoryLineSplitter::next(RawLine& line) {
  if (pos_ >= data_.size()) return false;
  std::size_t nl = data_.find('\n', pos_);
  split_at(data_, pos_, nl, line);
  line.number = ++line_number_;
  line.offset = pos_;
  pos_ += line.size();
  return true;
}

}  // namespace gcode
