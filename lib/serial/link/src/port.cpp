// termios2 lives in <asm/termbits.h>, which clashes with <termios.h>; the
// pseudo-terminal code that needs the latter is in pty.cpp.
#include <asm/termbits.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <thread>

#include <fmt/format.h>

#include "gcode/serial/link/port.hpp"

namespace gcode::serial {

namespace fs = std::filesystem;

namespace {

// The pid holding a flock() on the file `fd` is open on, from /proc/locks
// ("1: FLOCK  ADVISORY  WRITE 4242 00:1a:1234 0 EOF"); "" when not found.
std::string flock_holder(int fd) {
  struct stat st{};
  if (::fstat(fd, &st) != 0) return std::string();
  const std::string inode = fmt::format("{:02x}:{:02x}:{}", major(st.st_dev), minor(st.st_dev), st.st_ino);
  std::ifstream locks("/proc/locks");
  std::string n, kind, mode, access, pid, where;
  std::string rest;
  while (locks >> n >> kind >> mode >> access >> pid >> where) {
    std::getline(locks, rest);
    if (kind == "FLOCK" && where == inode) return pid;
  }
  return std::string();
}

// One program at a time on a printer's port: a second gc-send would
// interleave its lines with the print's (and set the baud rate, or pulse
// DTR and restart the board). Taken before anything is set on the port;
// it ends with the descriptor, a SIGKILL included. Advisory: it stops
// gc-sends (and programs that flock() likewise), not every program.
void lock_port(int fd, const std::string& path) {
  if (::flock(fd, LOCK_EX | LOCK_NB) == 0) return;
  const int e = errno;
  const std::string holder = e == EWOULDBLOCK ? flock_holder(fd) : std::string();
  ::close(fd);
  if (e != EWOULDBLOCK) throw std::runtime_error(fmt::format("cannot lock {}: {}", path, std::strerror(e)));
  throw std::runtime_error(fmt::format("the port {} is in use by another gc-send{} (one print per printer)", path,
                                       holder.empty() ? std::string() : " (pid " + holder + ")"));
}

}  // namespace

int open_serial_port(const std::string& path, const PortOptions& options) {
  int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error(fmt::format("cannot open {}: {}", path, std::strerror(errno)));
  lock_port(fd, path);
  struct termios2 tio{};
  if (ioctl(fd, TCGETS2, &tio) != 0) {
    int e = errno;
    ::close(fd);
    throw std::runtime_error(fmt::format("{} is not a serial port: {}", path, std::strerror(e)));
  }
  tio.c_iflag &= ~static_cast<tcflag_t>(IGNBRK | BRKINT | PARMRK | ISTRIP | INLCR | IGNCR | ICRNL | IXON | IXOFF | IXANY);
  tio.c_oflag &= ~static_cast<tcflag_t>(OPOST);
  tio.c_lflag &= ~static_cast<tcflag_t>(ECHO | ECHONL | ICANON | ISIG | IEXTEN);
  tio.c_cflag &= ~static_cast<tcflag_t>(CSIZE | PARENB | CSTOPB | CRTSCTS | CBAUD | (CBAUD << IBSHIFT));
  tio.c_cflag |= CS8 | CREAD | CLOCAL | BOTHER | (BOTHER << IBSHIFT);
  if (!options.reset) tio.c_cflag &= ~static_cast<tcflag_t>(HUPCL);  // closing must not restart the board either
  tio.c_ispeed = static_cast<speed_t>(options.baud);
  tio.c_ospeed = static_cast<speed_t>(options.baud);
  tio.c_cc[VMIN] = 1;  // with O_NONBLOCK: EAGAIN when empty; VMIN 0 would read as end of file
  tio.c_cc[VTIME] = 0;
  if (ioctl(fd, TCSETS2, &tio) != 0) {
    int e = errno;
    ::close(fd);
    throw std::runtime_error(fmt::format("cannot set {} to {} baud: {}", path, options.baud, std::strerror(e)));
  }
  if (options.reset) {
    // Arduino-style boards restart when DTR drops; the bootloader then needs
    // a moment before the firmware greets with "start".
    int dtr = TIOCM_DTR;
    if (ioctl(fd, TIOCMBIC, &dtr) == 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      ioctl(fd, TIOCMBIS, &dtr);
    }
  }
  return fd;
}

int wait_for_port(const std::string& path, const PortOptions& options, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  for (;;) {
    try {
      return open_serial_port(path, options);
    } catch (const std::runtime_error&) {
      if (std::chrono::steady_clock::now() >= end) throw;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
}

std::vector<PortInfo> list_serial_ports() {
  std::vector<PortInfo> ports;
  std::error_code ec;
  // udev's stable names say what is plugged in (maker, model, serial).
  for (const auto& e : fs::directory_iterator("/dev/serial/by-id", ec)) {
    fs::path target = fs::canonical(e.path(), ec);
    if (ec) continue;
    ports.push_back({target.string(), e.path().filename().string()});
  }
  for (const auto& e : fs::directory_iterator("/sys/class/tty", ec)) {
    std::string name = e.path().filename().string();
    if (name.rfind("ttyUSB", 0) != 0 && name.rfind("ttyACM", 0) != 0 && name.rfind("ttyAMA", 0) != 0) continue;
    std::string dev = "/dev/" + name;
    bool known = false;
    for (const PortInfo& p : ports) known = known || p.path == dev;
    if (known) continue;
    fs::path driver = fs::read_symlink(e.path() / "device" / "driver", ec);
    ports.push_back({dev, ec ? std::string() : driver.filename().string()});
  }
  std::sort(ports.begin(), ports.end(), [](const PortInfo& a, const PortInfo& b) { return a.path < b.path; });
  return ports;
}

}  // namespace gcode::serial
