#include <fcntl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include <fmt/format.h>

#include "gcode/serial/link/port.hpp"

namespace gcode::serial {

bool is_pseudo_terminal(int fd) {
  struct stat st {};
  if (fstat(fd, &st) != 0 || !S_ISCHR(st.st_mode)) return false;
  // Linux: Unix98 pty slaves (/dev/pts/N) have majors 136-143, BSD-style
  // ones (/dev/ttyp0) major 3.
  unsigned m = major(st.st_rdev);
  return (m >= 136 && m <= 143) || m == 3;
}

PseudoTerminal::PseudoTerminal(const std::string& link_path) : link_(link_path) {
  // A constructor that throws runs no destructor: what it opened it closes.
  auto fail = [this](std::string message) {
    int e = errno;
    if (slave_ >= 0) ::close(slave_);
    if (master_ >= 0) ::close(master_);
    slave_ = master_ = -1;
    throw std::runtime_error(fmt::format("{}: {}", message, std::strerror(e)));
  };
  master_ = posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (master_ < 0 || grantpt(master_) != 0 || unlockpt(master_) != 0) fail("cannot create a pseudo-terminal");
  char name[128];
  if (ptsname_r(master_, name, sizeof name) != 0) fail("ptsname");
  slave_path_ = name;
  slave_ = ::open(name, O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (slave_ < 0) fail("cannot open " + slave_path_);
  // Raw on both sides: no echo, no line editing, no CR/LF translation.
  termios tio{};
  tcgetattr(slave_, &tio);
  cfmakeraw(&tio);
  tcsetattr(slave_, TCSANOW, &tio);
  tcgetattr(master_, &tio);
  cfmakeraw(&tio);
  tcsetattr(master_, TCSANOW, &tio);
  ::unlink(link_.c_str());
  if (::symlink(slave_path_.c_str(), link_.c_str()) != 0) fail("cannot create the link " + link_);
}

PseudoTerminal::~PseudoTerminal() {
  ::unlink(link_.c_str());
  if (slave_ >= 0) ::close(slave_);
  if (master_ >= 0) ::close(master_);
}

}  // namespace gcode::serial
