#pragma once
// What a piece of code writes to a file descriptor (standard error or
// output), for tests of messages written straight to them; and standard
// input taken from a pipe for the length of a call.
#include <unistd.h>

#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>
#include <thread>

#include "test_support.hpp"

namespace gctest {

inline std::string captured(int fd, const std::function<void()>& body) {
  std::string path = temp_dir() + "/captured";
  std::fflush(nullptr);
  int saved = ::dup(fd);
  std::FILE* f = std::fopen(path.c_str(), "w");
  ::dup2(::fileno(f), fd);
  try {
    body();
  } catch (...) {
    std::fflush(nullptr);
    ::dup2(saved, fd);
    ::close(saved);
    std::fclose(f);
    throw;
  }
  std::fflush(nullptr);
  ::dup2(saved, fd);
  ::close(saved);
  std::fclose(f);
  return read_file(path);
}

inline std::string stderr_of(const std::function<void()>& body) { return captured(2, body); }
inline std::string stdout_of(const std::function<void()>& body) { return captured(1, body); }

// Runs `body` with standard input a pipe that delivers `text` (not seekable).
inline void with_piped_stdin(const std::string& text, const std::function<void()>& body) {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("pipe");
  std::thread writer([fd = fds[1], &text] {
    for (std::size_t at = 0; at < text.size();) {
      ssize_t n = ::write(fd, text.data() + at, text.size() - at);
      if (n <= 0) break;
      at += static_cast<std::size_t>(n);
    }
    ::close(fd);
  });
  int saved = ::dup(0);
  ::dup2(fds[0], 0);
  ::close(fds[0]);
  try {
    body();
  } catch (...) {
    ::dup2(saved, 0);
    ::close(saved);
    writer.join();
    throw;
  }
  ::dup2(saved, 0);
  ::close(saved);
  writer.join();
}

}  // namespace gctest
