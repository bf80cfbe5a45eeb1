#pragma once
// Serial ports and pseudo-terminals.
//
// Ports are set up with Linux's termios2 and BOTHER, which takes any baud
// rate as a number: Marlin boards commonly run at 250000 or 500000, rates
// the classic B-constants of termios cannot express. 8N1, raw, no flow
// control. A pseudo-terminal path (a virtual printer) opens the same way.
#include <string>
#include <vector>

namespace gcode::serial {

struct PortOptions {
  int baud = 250000;
  bool reset = false;  // pulse DTR low to restart an Arduino-style board
};

// Opens and configures `path`; the descriptor is non-blocking and holds an
// exclusive flock() on the port, taken before anything is set on it. Throws
// std::runtime_error with a readable message (another gc-send holding the
// port is named by its pid).
int open_serial_port(const std::string& path, const PortOptions& options);

// open_serial_port, tried again every tenth of a second for up to `seconds`
// while the port is away (a USB board's node comes back after a drop).
// Throws the last attempt's error when it did not come back in time.
int wait_for_port(const std::string& path, const PortOptions& options, double seconds);

// Whether `fd` is a pseudo-terminal (a simulated printer, Klipper's
// /tmp/printer): its bytes cross at once, whatever baud rate is set.
bool is_pseudo_terminal(int fd);

struct PortInfo {
  std::string path;         // /dev/ttyACM0
  std::string description;  // the /dev/serial/by-id name or the driver
};
// Candidate printer ports: USB serial adapters and CDC-ACM boards.
std::vector<PortInfo> list_serial_ports();

// A pseudo-terminal whose slave side is reachable through a symlink, so that
// any host program can open it like a serial port. The slave is kept open
// here too, so the master never sees a hang-up between clients.
class PseudoTerminal {
 public:
  explicit PseudoTerminal(const std::string& link_path);
  ~PseudoTerminal();  // removes the symlink
  PseudoTerminal(const PseudoTerminal&) = delete;
  PseudoTerminal& operator=(const PseudoTerminal&) = delete;
  int master() const { return master_; }
  const std::string& slave_path() const { return slave_path_; }

 private:
  int master_ = -1;
  int slave_ = -1;
  std::string slave_path_;
  std::string link_;
};

}  // namespace gcode::serial
