#include "gcode/core/file_io.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "gcode/core/output_buffer.hpp"

namespace gcode {

namespace {
std::string errno_message(const std::string& what) { return what + ": " + std::strerror(errno); }

// See InputFile::widen_pipe.
void widen_pipe_fd(int fd) {
  struct stat st {};
  if (::fstat(fd, &st) == 0 && S_ISFIFO(st.st_mode)) (void)::fcntl(fd, F_SETPIPE_SZ, 1 << 20);
}
}  // namespace

InputFile::InputFile(const std::string& path) {
  if (path.empty() || path == "-") {
    fd_ = 0;
    name_ = "<stdin>";
    return;
  }
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) throw std::runtime_error(errno_message(path));
  struct stat st {};
  if (::fstat(fd_, &st) == 0 && S_ISDIR(st.st_mode)) {
    ::close(fd_);
    throw std::runtime_error(path + ": is a directory");
  }
  owned_ = true;
  name_ = path;
}

void InputFile::make_seekable() {
  if (::lseek(fd_, 0, SEEK_CUR) >= 0) return;
  char templ[] = "/tmp/gc-spool-XXXXXX";
  int tmp = ::mkstemp(templ);
  if (tmp < 0) throw std::runtime_error(errno_message("temp file"));
  ::unlink(templ);
  std::vector<char> buffer(1 << 18);
  for (;;) {
    ssize_t n = ::read(fd_, buffer.data(), buffer.size());
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      ::close(tmp);
      throw std::runtime_error(errno_message(name_));
    }
    for (ssize_t done = 0; done < n;) {
      ssize_t w = ::write(tmp, buffer.data() + done, static_cast<std::size_t>(n - done));
      if (w < 0) {
        if (errno == EINTR) continue;
        ::close(tmp);
        throw std::runtime_error(errno_message("temp file"));
      }
      done += w;
    }
  }
  if (owned_) ::close(fd_);
  fd_ = tmp;
  owned_ = true;
  rewind();
}

void InputFile::rewind() {
  if (::lseek(fd_, 0, SEEK_SET) < 0) throw std::runtime_error(errno_message(name_));
}

void InputFile::widen_pipe() { widen_pipe_fd(fd_); }

InputFile::~InputFile() {
  if (owned_) ::close(fd_);
}

OutputFile::OutputFile(const std::string& path, const std::string& in_place_of) {
  if (!in_place_of.empty()) {
    target_ = in_place_of;
    temp_ = in_place_of + ".gc-tmp-XXXXXX";
    fd_ = ::mkstemp(temp_.data());
    if (fd_ < 0) throw std::runtime_error(errno_message(temp_));
    struct stat st {};
    if (::stat(in_place_of.c_str(), &st) == 0) ::fchmod(fd_, st.st_mode & 07777);
    owned_ = true;
    return;
  }
  if (path.empty() || path == "-") return;
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error(errno_message(path));
  owned_ = true;
}

void OutputFile::widen_pipe() { widen_pipe_fd(fd_); }

OutputFile::~OutputFile() {
  if (owned_) ::close(fd_);
  if (!temp_.empty()) ::unlink(temp_.c_str());
}

void OutputFile::commit() {
  if (!owned_) return;
  if (::fsync(fd_) != 0 && errno != EINVAL) throw std::runtime_error(errno_message("fsync"));
  if (::close(fd_) != 0) throw std::runtime_error(errno_message("close"));
  owned_ = false;
  if (!temp_.empty()) {
    if (::rename(temp_.c_str(), target_.c_str()) != 0) throw std::runtime_error(errno_message(target_));
    temp_.clear();
  }
}

}  // namespace gcode
