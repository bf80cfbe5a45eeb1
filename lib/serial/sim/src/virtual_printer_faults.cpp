// The virtual printer's resets and link drops (virtual_fault.hpp): what a
// board loses when it restarts, and what it keeps doing while its USB link
// is gone.
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "gcode/serial/sim/virtual_printer.hpp"

namespace gcode::serial {

void VirtualPrinter::note(const std::string& text) {
  if (log_ == nullptr) return;
  std::fprintf(log_, "# %s\n", text.c_str());
  std::fflush(log_);
}

void VirtualPrinter::reset(double t) {
  now_ = std::max(now_, t);
  ++stats_.resets;
  // The moves that had left the queue (their ok sent, their log line
  // written) but not the planner never ran: the log says which.
  std::string lost;
  for (long long n : block_numbers_) lost += fmt::format(" N{}", n);
  lost += ";";
  for (const Command& c : queue_) lost += fmt::format(" N{}", c.number);
  note(fmt::format("reset at {:.6f}: lost from the planner and queue{}", t, lost));
  wire_.clear(t);
  rx_.clear();
  rx_head_ = 0;
  partial_.clear();
  emergency_.clear();
  queue_.clear();
  planner_.clear();
  lengths_.clear();
  block_numbers_.clear();
  empty_since_ = t;
  wait_ = Wait::None;
  after_ = After::Nothing;
  ok_sent_ = false;
  heating_bed_ = false;
  autoreport_ = 0;
  next_report_ = std::numeric_limits<double>::infinity();
  hotend_target_ = bed_target_ = 0;
  state_ = MachineState{};
  homed_ = false;
  homing_fails_ = false;
  last_n_ = 0;
  halted_ = silent_ = false;
  flavour_.restarted();
  // The part is still on the bed: the layer count (the printer's own view
  // of heights) goes on.
  std::vector<std::string> greeting = dialect_->restart_greeting(config_.greeting);
  if (config_.greeting == GreetingForm::CutLine && !greeting.empty() && !outage_.down()) {
    // The first half of the line it was sending, the greeting straight after.
    std::string_view cut = std::string_view(last_sent_).substr(0, (last_sent_.size() + 1) / 2);
    stats_.tx_bytes += cut.size();
    wire_.transmit_bytes(cut, now_);
  }
  for (const std::string& line : greeting) send(line);
}

void VirtualPrinter::drop_link(double t, double seconds, bool reset_after) {
  now_ = std::max(now_, t);
  ++stats_.link_drops;
  note(fmt::format("link down at {:.6f} for {:g} s{}", t, seconds, reset_after ? ", then a reset" : ""));
  wire_.clear(t);
  outage_.begin(t, seconds, reset_after);
}

void VirtualPrinter::link_up(double t) {
  const bool reset_now = outage_.end();
  note(fmt::format("link up at {:.6f}", t));
  if (reset_now) reset(t);
}

void VirtualPrinter::fire(const ScheduledFault& fault, double t) {
  switch (fault.kind) {
    case ScheduledFault::Kind::Reset: reset(t); break;
    case ScheduledFault::Kind::Drop: drop_link(t, fault.seconds, false); break;
    case ScheduledFault::Kind::DropReset: drop_link(t, fault.seconds, true); break;
  }
}

}  // namespace gcode::serial
