#pragma once
// The simulated printer at the far end of gc-send's line (link/printer_link.hpp):
// a VirtualPrinter in the same process, behind one end of a socketpair, driven
// by the event loop (VirtualLink). gc-send's front end chooses it for
// `--port virtual[:OPTIONS]`.
#include <cstdio>
#include <memory>
#include <string>

#include "gcode/serial/link/event_loop.hpp"
#include "gcode/serial/link/printer_link.hpp"
#include "gcode/serial/sim/virtual_link.hpp"
#include "gcode/serial/sim/virtual_printer.hpp"

namespace gcode::serial {

// Whether a --port value names the simulated printer: "virtual" or "virtual:OPTIONS".
bool is_virtual_port(const std::string& port);

class VirtualPrinterLink : public PrinterLink, public FarMotion {
 public:
  // Throws std::runtime_error when the socketpair or the model's log (config.log_path) cannot be made.
  VirtualPrinterLink(EventLoop& loop, const VirtualPrinterConfig& config);
  ~VirtualPrinterLink() override;
  VirtualPrinterLink(const VirtualPrinterLink&) = delete;
  VirtualPrinterLink& operator=(const VirtualPrinterLink&) = delete;

  // "virtual printer: executed ...": what the model did, by its own clock.
  std::string summary() const override;
  FarMotion* motion() override { return this; }

  double now() const override { return link_->simulated_now(); }
  double travelled(double t) const override { return printer_->travelled(t); }
  void watch(long long number) override { printer_->watch(number); }
  bool watched(double& end, double& queued) const override;

 private:
  int model_fd_ = -1;  // the socketpair's other end (gc-send's is fd())
  std::FILE* log_ = nullptr;
  std::unique_ptr<VirtualPrinter> printer_;
  std::unique_ptr<VirtualLink> link_;
};

}  // namespace gcode::serial
