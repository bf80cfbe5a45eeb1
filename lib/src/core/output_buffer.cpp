#include "gcode/core/output_buffer.hpp"

#include <cerrno>
#include <csignal>
#include <system_error>
#include <unistd.h>

namespace gcode {

OutputBuffer::OutputBuffer(int fd, std::size_t capacity)
    : fd_(fd), capacity_(capacity), data_(capacity) {
  // EPIPE as an error code rather than a signal that kills us mid-message.
  std::signal(SIGPIPE, SIG_IGN);
}

OutputBuffer::OutputBuffer(std::string& target, std::size_t capacity)
    : fd_(-1), target_(&target), capacity_(capacity), data_(capacity) {}

OutputBuffer::~OutputBuffer() {
  try {
    flush();
  } catch (...) {
  }
}

void OutputBuffer::flush() {
  if (used_ == 0) return;
  std::size_t n = used_;
  used_ = 0;
  write_all(data_.data(), n);
  total_ += n;
}

void OutputBuffer::write_slow(std::string_view bytes) {
  flush();
  if (bytes.size() >= capacity_) {
    write_all(bytes.data(), bytes.size());
    total_ += bytes.size();
  } else {
    std::char_traits<char>::copy(data_.data(), bytes.data(), bytes.size());
    used_ = bytes.size();
  }
}

void OutputBuffer::write_all(const char* p, std::size_t n) {
  if (target_ != nullptr) {
    target_->append(p, n);
    return;
  }
  while (n > 0) {
    ssize_t w = ::write(fd_, p, n);
    if (w >= 0) {
      p += w;
      n -= static_cast<std::size_t>(w);
      continue;
    }
    if (errno == EINTR) continue;
    if (errno == EPIPE) throw BrokenPipe();
    throw std::system_error(errno, std::generic_category(), "write");
  }
}

}  // namespace gcode
