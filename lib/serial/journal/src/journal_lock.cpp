#include "gcode/serial/journal/journal_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "gcode/serial/journal/journal.hpp"
#include "gcode/serial/link/private_path.hpp"

namespace gcode::serial {

namespace {

// The pid the holder wrote, or "" (it may be between taking the lock and
// writing its pid, or an older gc-send that wrote none).
std::string holder_of(int fd) {
  char buf[32] = {};
  ssize_t n = ::pread(fd, buf, sizeof buf - 1, 0);
  if (n <= 0) return std::string();
  std::string pid(buf, static_cast<std::size_t>(n));
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos) return std::string();
  return pid;
}

}  // namespace

JournalLock::JournalLock(const std::string& journal_path) : path_(journal_path + ".lock") {
  make_private_folder(path_);
  std::string problem = folder_problem(folder_of(path_), "journal");
  if (!problem.empty()) throw JournalError(problem);
  fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0600);
  if (fd_ < 0)
    throw JournalError(fmt::format("cannot open the journal's lock {}: {}", path_, std::strerror(errno)));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    int err = errno;
    std::string holder = err == EWOULDBLOCK ? holder_of(fd_) : std::string();
    ::close(fd_);
    fd_ = -1;
    if (err != EWOULDBLOCK)
      throw JournalError(fmt::format("cannot lock the journal {}: {}", journal_path, std::strerror(err)));
    throw JournalError(fmt::format("the journal {} is in use by another gc-send{} (one print per journal: let it "
                                   "end, or cancel it through its control FIFO, before starting or resuming this one)",
                                   journal_path, holder.empty() ? std::string() : " (pid " + holder + ")"));
  }
  // Written once the lock is held, so the pid a refused one reads is the
  // holder's. Should writing fail, the lock holds all the same: only the
  // refusal's pid is missing.
  std::string pid = fmt::format("{}\n", ::getpid());
  if (::ftruncate(fd_, 0) != 0) return;
  if (::pwrite(fd_, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) return;
}

JournalLock::~JournalLock() {
  // The file stays: removing it would let a third gc-send lock a new file
  // while a second already opened the old one's inode.
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace gcode::serial
