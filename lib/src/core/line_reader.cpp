#include "gcode/core/line_reader.hpp"

#include <cerrno>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <cstring>
#include <system_error>
#include <unistd.h>

namespace gcode {

namespace {

// The line [first, nl) and its ending ("\n" or "\r\n"), nl at a '\n'.
inline void split_before(const char* first, const char* nl, RawLine& line) {
  const char* text_end = nl > first && nl[-1] == '\r' ? nl - 1 : nl;
  line.text = std::string_view(first, static_cast<std::size_t>(text_end - first));
  line.ending = std::string_view(text_end, static_cast<std::size_t>(nl + 1 - text_end));
}

// Fills `line` from data[start, nl) where nl is the index of '\n' or npos
// (the last line, without an ending).
void split_at(std::string_view data, std::size_t start, std::size_t nl, RawLine& line) {
  if (nl == std::string_view::npos) {
    line.text = data.substr(start);
    line.ending = {};
    return;
  }
  split_before(data.data() + start, data.data() + nl, line);
}

// The first '\n' in [p, stop), or nullptr. A G-code line is some 25 bytes:
// two 16-byte compares find its end for less than memchr's call and setup
// (callgrind); a long line goes on to memchr after 64 bytes.
inline const char* find_newline(const char* p, const char* stop) {
#if defined(__SSE2__)
  const __m128i newline = _mm_set1_epi8('\n');
  for (int i = 0; i < 4 && stop - p >= 16; ++i, p += 16) {
    __m128i block;
    std::memcpy(&block, p, sizeof block);
    const unsigned hits = static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi8(block, newline)));
    if (hits != 0) return p + __builtin_ctz(hits);
  }
#endif
  return static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(stop - p)));
}

}  // namespace

std::size_t read_some(int fd, char* out, std::size_t bytes) {
  for (;;) {
    ssize_t n = ::read(fd, out, bytes);
    if (n >= 0) return static_cast<std::size_t>(n);
    if (errno == EINTR) continue;
    throw std::system_error(errno, std::generic_category(), "read");
  }
}

LineSplitter::LineSplitter(std::size_t block_size)
    : block_size_(block_size < 16 ? 16 : block_size), buffer_(block_size_ * 2) {}

void LineSplitter::make_room(std::size_t bytes) {
  // Move the unfinished line to the front; grow only when one line fills it.
  if (begin_ > 0) {
    std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
    end_ -= begin_;
    begin_ = 0;
  }
  if (buffer_.size() - end_ < bytes) {
    std::size_t size = buffer_.size();
    while (size - end_ < bytes) size *= 2;
    buffer_.resize(size);
  }
}

char* LineSplitter::room() {
  if (buffer_.size() - end_ < block_size_) make_room(block_size_);
  return buffer_.data() + end_;
}

void LineSplitter::append(std::string_view bytes) {
  if (buffer_.size() - end_ < bytes.size()) make_room(bytes.size());
  std::memcpy(buffer_.data() + end_, bytes.data(), bytes.size());
  end_ += bytes.size();
}

bool LineSplitter::next(RawLine& line) {
  const char* base = buffer_.data();
  const char* hit = find_newline(base + begin_ + scanned_, base + end_);
  if (hit != nullptr) {
    split_before(base + begin_, hit, line);
  } else if (ended_ && begin_ < end_) {
    split_at(std::string_view(base, end_), begin_, std::string_view::npos, line);
  } else {
    scanned_ = end_ - begin_;  // a long line is scanned once, not once per block
    return false;
  }
  scanned_ = 0;
  line.number = ++line_number_;
  line.offset = consumed_;
  consumed_ += line.size();
  begin_ += line.size();
  return true;
}

LineReader::LineReader(int fd, std::size_t block_size) : fd_(fd), splitter_(block_size) {}

bool LineReader::fill() {
  if (splitter_.ended()) return false;
  char* room = splitter_.room();
  std::size_t n = read_some(fd_, room, splitter_.room_size());
  if (n == 0) {
    splitter_.end_of_input();
    return false;
  }
  splitter_.commit(n);
  return true;
}

bool LineReader::next(RawLine& line) {
  while (!splitter_.next(line)) {
    if (splitter_.ended()) return false;
    fill();
  }
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
