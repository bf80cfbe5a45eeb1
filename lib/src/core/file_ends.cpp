#include "gcode/core/file_ends.hpp"

#include <sys/stat.h>
#include <unistd.h>

namespace gcode {

namespace {

bool read_at(int fd, std::string& out, std::size_t size, off_t at) {
  out.resize(size);
  std::size_t done = 0;
  while (done < size) {
    ssize_t n = ::pread(fd, out.data() + done, size - done, at + static_cast<off_t>(done));
    if (n < 0) return false;
    if (n == 0) break;
    done += static_cast<std::size_t>(n);
  }
  out.resize(done);
  return true;
}

}  // namespace

bool read_file_ends(int fd, std::size_t head_bytes, std::size_t tail_bytes, FileEnds& ends) {
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) return false;
  auto size = static_cast<std::size_t>(st.st_size);
  ends.tail.clear();
  if (size <= head_bytes + tail_bytes) return read_at(fd, ends.head, size, 0);
  if (!read_at(fd, ends.head, head_bytes, 0)) return false;
  ends.head.resize(ends.head.rfind('\n') + 1);  // whole lines only
  return read_at(fd, ends.tail, tail_bytes, static_cast<off_t>(size - tail_bytes));
}

}  // namespace gcode
