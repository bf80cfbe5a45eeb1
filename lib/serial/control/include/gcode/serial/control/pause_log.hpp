#pragma once
// The pauses of one gc-send print, for its summary and status: when each was
// asked for and reached, and (with a simulated printer's exact figures) how
// long and how far the nozzle went on after the request.
#include <cstdint>
#include <string>
#include <vector>

namespace gcode::serial {

// One pause.
struct PauseRecord {
  std::string request;          // "pause", "pause now", "@pause", "//action:pause"
  int layer = 0;                // the layer the request came in
  int paused_before_layer = 0;  // the block went before this layer (0: mid-layer or end code)
  std::uint64_t input_line = 0; // the last input line sent before the block
  double wall_request = 0;      // when the request came (monotonic)
  double wall_paused = -1;      // when the printer had done the block
  double printer_request = -1;  // MotionProbe: printer time of the request
  double latency_s = -1;        // MotionProbe: from the request to the motion's end
  double latency_mm = -1;       // MotionProbe: the path the nozzle went meanwhile
  long long block_number = 0;   // the block's first line number
  bool block = false;           // gc-send's own block (not the file's pause)
  double path_at_request = -1;  // MotionProbe: the path travelled by the request
};

class PauseLog {
 public:
  // A pause is asked for: `printer_time` from a MotionProbe, else -1.
  PauseRecord& start(std::string request, int layer, double wall_now, double printer_time);
  // The pause asked for is called off before it happened.
  void call_off() { records_.pop_back(); }
  // The printer has done the block (the first time it is seen idle).
  void reached(double wall_now) { records_.back().wall_paused = wall_now; }
  // The print goes on: the time stood still counts in paused_seconds.
  void resumed(double wall_now);

  bool empty() const { return records_.empty(); }
  PauseRecord& current() { return records_.back(); }
  const PauseRecord& current() const { return records_.back(); }
  // The newest pause is asked for or its block sent, not done yet.
  bool reaching() const { return !records_.empty() && records_.back().wall_paused < 0; }
  const std::vector<PauseRecord>& records() const { return records_; }
  // Wall seconds stood paused (the block done until the resume); `paused`:
  // the newest pause goes on, and counts until `wall_now`.
  double paused_seconds(double wall_now, bool paused) const;

 private:
  std::vector<PauseRecord> records_;
  double resumed_seconds_ = 0;  // of the pauses resumed
};

}  // namespace gcode::serial
