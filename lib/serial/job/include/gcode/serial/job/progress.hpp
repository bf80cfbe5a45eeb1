#pragma once
// gc-send's progress: on a terminal one live line on stderr, rewritten in
// place; elsewhere a plain line every few seconds; and, when asked, the same
// figures as JSON in a status file, rewritten atomically (temp file +
// rename) so a reader never sees half of it.
#include <cstdint>
#include <string>
#include <string_view>

#include "gcode/core/diagnostics.hpp"

namespace gcode::serial {

struct ProgressSnapshot {
  std::string_view state;       // printing, pausing, paused, cancelling, done
  int layer = 0;                // 0: start code
  int layers = 0;               // as far as known
  double percent = -1;          // of the input's bytes (-1: unknown, a pipe)
  std::uint64_t lines = 0;      // numbered lines sent
  double lines_per_second = 0;
  double elapsed = 0;           // seconds since the first line
  double eta = -1;              // seconds (-1: unknown)
  double speed = 1;             // `speed F`
  std::string_view temperatures;  // the printer's last report
  int pauses = 0;
  double last_pause_mm = -1;    // the last pause's latency (a simulated printer tells)
  double last_pause_s = -1;
  int last_pause_layer = 0;     // the layer the last pause was asked in
  int last_paused_before = 0;   // the layer it paused before (0: mid-layer)
  int resets = 0;               // printer resets the print came back from
  double redone_mm = 0;         // what may have printed twice after them, mm
  std::string objects;          // "[...], \"cancelled\": [...]" (ObjectCancel::json), "" for none
};

enum class ProgressMode : std::uint8_t { Off, Live, Plain };

struct ProgressOptions {
  ProgressMode mode = ProgressMode::Off;
  double interval = 5;          // seconds between plain lines (a live line: 0.25)
  std::string status_file;      // "" = none
};

// The time left, from the estimator: the printer seconds it gives the whole
// input and what was handed over so far, paced by how the print ran (wall
// seconds spent printing, pauses left out, per estimated second: a printer
// slower than its model, a time scale, a speed factor). -1 until a
// twentieth of the estimate and five seconds of printing have run, or without an
// estimate (then the caller goes by the rate of the input).
double estimated_remaining(double estimated_total, double estimated_done, double printing_seconds);

// The time left of one print: the estimator's seconds (estimated_remaining)
// paced from layer 1 on, the start code's heating not being in the estimate;
// else the rate of the input. Its times are the caller's clock.
class PrintEta {
 public:
  // The estimator's printer seconds for the whole input (0: none, as for a
  // swapped-in file).
  void set_estimate(double seconds) { estimate_ = seconds; }
  // Layer 1 began at `now`: `estimated_done` printer seconds were handed
  // over by then and `paused` seconds stood paused. Once; later calls are
  // ignored.
  void layer_one(double now, double estimated_done, double paused);
  bool pacing() const { return origin_wall_ >= 0; }
  // Seconds left, -1 unknown: `estimated_done` and `paused` as above, now;
  // `percent` of the input sent (-1: unknown) and `elapsed` seconds since
  // the first line for the rate of the input.
  double remaining(double now, double estimated_done, double paused, double percent, double elapsed) const;

 private:
  double estimate_ = 0;
  double origin_wall_ = -1;     // when layer 1 began (the pace counts from there)
  double origin_estimate_ = 0;  // the estimate handed over by then
  double origin_paused_ = 0;    // the seconds stood paused by then
};

// "printing  layer 12/40  31.0 %  812 lines/s  0:42 elapsed  ETA 1:33"
std::string progress_line(const ProgressSnapshot& s);
std::string progress_json(const ProgressSnapshot& s);

class Progress {
 public:
  // Plain lines go out through `diagnostics` (the tool's name before them).
  Progress(ProgressOptions options, Diagnostics& diagnostics);
  ~Progress();  // ends a live line
  // Writes the line (when its interval has passed, or `force`) and the
  // status file (when the snapshot changed state or layer, or `force`).
  void report(const ProgressSnapshot& s, double now, bool force);
  // `status`: the line on stderr whatever the mode (for the status command).
  void print_line(const ProgressSnapshot& s);
  double interval() const;

 private:
  void write_status(const ProgressSnapshot& s);

  ProgressOptions options_;
  Diagnostics& diag_;
  double last_line_ = -1e300;
  bool live_shown_ = false;
  std::string last_state_;
  int last_layer_ = -1;
  std::string last_objects_;
  double last_status_ = -1e300;
};

}  // namespace gcode::serial
