#include "gcode/serial/control/control_fifo.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include <fmt/format.h>

#include "gcode/core/text.hpp"
#include "gcode/serial/link/private_path.hpp"

namespace gcode::serial {

namespace {

// Text a person or script writes: printable ASCII, tabs, UTF-8 bytes.
bool is_text(unsigned char c) { return c >= 0x20 ? c != 0x7f : c == '\t' || c == '\r'; }

}  // namespace

ControlParser::ControlParser(Handler on_command, JunkHandler on_junk)
    : on_command_(std::move(on_command)), on_junk_(std::move(on_junk)) {
  line_.reserve(kMaxLine);
}

void ControlParser::junk(std::string_view why) {
  if (reported_) return;
  reported_ = true;
  if (on_junk_) on_junk_(why);
}

void ControlParser::line_done() {
  if (skipping_) {
    skipping_ = false;
    line_.clear();
    return;
  }
  std::string_view text = trim(line_);
  if (!text.empty()) {
    ControlCommand c = parse_control_command(text);
    if (c.verb == nullptr && reported_) {
      // Between runs of junk: more of the same, not a person's typo.
      junk_bytes_ += line_.size() + 1;
    } else {
      ++commands_;
      if (c.verb != nullptr) reported_ = false;
      on_command_(c);
    }
  }
  line_.clear();
}

void ControlParser::feed(std::string_view bytes) {
  for (char ch : bytes) {
    if (ch == '\n') {
      line_done();
      continue;
    }
    if (skipping_) {
      ++junk_bytes_;
      continue;
    }
    if (!is_text(static_cast<unsigned char>(ch))) {
      junk_bytes_ += line_.size() + 1;
      line_.clear();
      skipping_ = true;
      junk("binary bytes in the control FIFO: lines dropped");
      continue;
    }
    if (line_.size() >= kMaxLine) {
      junk_bytes_ += line_.size() + 1;
      line_.clear();
      skipping_ = true;
      junk(fmt::format("a line of more than {} bytes in the control FIFO: dropped", kMaxLine));
      continue;
    }
    line_ += ch;
  }
}

std::string default_control_path(std::string_view port) {
  std::string name = port_file_name(port);
  const char* runtime = std::getenv("XDG_RUNTIME_DIR");
  std::string dir = runtime != nullptr && runtime[0] == '/' ? std::string(runtime) + "/gc-send"
                                                            : fmt::format("/tmp/gc-send-{}", ::getuid());
  return dir + "/" + name + ".fifo";
}

std::string control_path_problem(const std::string& path, unsigned uid) {
  struct stat st{};
  if (::lstat(path.c_str(), &st) != 0) return fmt::format("{}: {}", path, std::strerror(errno));
  if (!S_ISFIFO(st.st_mode)) return fmt::format("{} exists and is not a FIFO", path);
  if (st.st_uid != uid) return fmt::format("{} belongs to another user (uid {})", path, st.st_uid);
  if ((st.st_mode & (S_IWGRP | S_IWOTH)) != 0)
    return fmt::format("{} can be written by {} (mode {:o}): anyone could pause or cancel the print; chmod 600 it",
                       path, (st.st_mode & S_IWOTH) != 0 ? "others" : "its group", st.st_mode & 07777);
  return std::string();
}

ControlFifo::ControlFifo(std::string path) : path_(std::move(path)) {
  struct stat st{};
  if (::lstat(path_.c_str(), &st) != 0) {
    if (errno != ENOENT) throw std::runtime_error(fmt::format("control FIFO {}: {}", path_, std::strerror(errno)));
    std::size_t slash = path_.rfind('/');
    if (slash != std::string::npos && slash > 0) {
      std::string dir = path_.substr(0, slash);
      // Only the last folder is made (the runtime dir or /tmp is there).
      if (::mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST)
        throw std::runtime_error(fmt::format("cannot create {}: {}", dir, std::strerror(errno)));
    }
    bool made = ::mkfifo(path_.c_str(), 0600) == 0;
    if (!made && errno != EEXIST)
      throw std::runtime_error(fmt::format("cannot create the control FIFO {}: {}", path_, std::strerror(errno)));
    // The umask may only take bits away; make sure of the mode anyway.
    if (made) {
      ::chmod(path_.c_str(), 0600);
      created_ = true;
    }
  }
  // Its folder too: someone else who may write there could swap the FIFO
  // (a sticky folder such as /tmp only lets owners remove their files).
  std::string folder = folder_problem(folder_of(path_), "control FIFO");
  if (!folder.empty()) throw std::runtime_error(folder);
  std::string problem = control_path_problem(path_, ::getuid());
  if (!problem.empty()) throw std::runtime_error("control FIFO refused: " + problem);
  fd_ = ::open(path_.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC | O_NOFOLLOW);
  if (fd_ < 0) throw std::runtime_error(fmt::format("cannot open the control FIFO {}: {}", path_, std::strerror(errno)));
  // Checked again on what was opened: the path may have been swapped between.
  struct stat opened{};
  if (::fstat(fd_, &opened) != 0 || !S_ISFIFO(opened.st_mode) || opened.st_uid != ::getuid()) {
    ::close(fd_);
    fd_ = -1;
    throw std::runtime_error(fmt::format("control FIFO refused: {} changed while it was opened", path_));
  }
}

ControlFifo::~ControlFifo() {
  if (fd_ >= 0) ::close(fd_);
  if (created_) ::unlink(path_.c_str());
}

void ControlFifo::read_into(ControlParser& parser) {
  char buf[4096];
  for (;;) {
    ssize_t n = ::read(fd_, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;  // EAGAIN: nothing more now (O_RDWR: never end of file)
    parser.feed(std::string_view(buf, static_cast<std::size_t>(n)));
  }
}

}  // namespace gcode::serial
