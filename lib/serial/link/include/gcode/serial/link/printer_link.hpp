#pragma once
// A printer at the far end of gc-send's line, as gc-send's job talks to it:
// a device or pseudo-terminal (PortLink, below) or the simulated printer
// (sim/virtual_printer_link.hpp). The front end chooses which, so the job
// knows no simulated printer.
#include <string>

#include "gcode/serial/link/port.hpp"

namespace gcode::serial {

// The far end's own motion, where it can tell (the simulated printer does):
// the pause's latency figures.
class FarMotion {
 public:
  virtual ~FarMotion() = default;
  virtual double now() const = 0;                  // printer seconds
  virtual double travelled(double t) const = 0;    // path (mm) travelled by then
  virtual void watch(long long number) = 0;        // the first command of the pause block
  // When the motion ahead of the watched command ended and the path queued
  // before it; false while it has not run yet.
  virtual bool watched(double& end, double& queued) const = 0;
};

class PrinterLink {
 public:
  virtual ~PrinterLink() = default;
  PrinterLink(const PrinterLink&) = delete;
  PrinterLink& operator=(const PrinterLink&) = delete;

  // The descriptor gc-send talks on (-1 once given up).
  int fd() const { return fd_; }
  // The session closed the descriptor when it replaced a lost port: not closed again here.
  void release() { fd_ = -1; }
  double baud() const { return baud_; }
  double time_scale() const { return scale_; }
  // A pseudo-terminal: its bytes cross at once, whatever the baud rate.
  bool pty() const { return pty_; }

  // Whether a line that went away may come back (a USB board's node after
  // a drop): a device's may, the simulated printer's ends with it.
  virtual bool reconnects() const { return false; }
  // The line that went away, opened again within `seconds` (reconnects() only).
  virtual void reopen(double seconds) { (void)seconds; }
  // What the far end tells of the print at its end (a summary line), or "".
  virtual std::string summary() const { return {}; }
  // Its motion, or nullptr where it cannot tell (a real printer).
  virtual FarMotion* motion() { return nullptr; }

 protected:
  PrinterLink(int fd, double baud, double scale, bool pty) : fd_(fd), baud_(baud), scale_(scale), pty_(pty) {}
  int fd_;

 private:
  double baud_;
  double scale_;
  bool pty_;
};

// A printer on a serial port or a pseudo-terminal (port.hpp).
class PortLink : public PrinterLink {
 public:
  // Takes `fd`, open on `path` (open_serial_port).
  PortLink(std::string path, const PortOptions& options, int fd);
  ~PortLink() override;
  PortLink(const PortLink&) = delete;
  PortLink& operator=(const PortLink&) = delete;

  bool reconnects() const override { return true; }
  void reopen(double seconds) override;

 private:
  std::string path_;
  PortOptions options_;
};

}  // namespace gcode::serial
