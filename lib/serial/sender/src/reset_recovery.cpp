#include "gcode/serial/sender/reset_recovery.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gcode::serial {

void ResetRecovery::hold_base(long long n, const MachineState& after, const ResumeTrack& track,
                              std::uint64_t source_line, int layer) {
  base_number_ = n;
  base_ = PrintStep();
  base_.drains = true;
  base_.after = after;
  base_.track = track;
  base_.source_line = source_line;
  base_.layer = layer;
  for (int a = 0; a < 3; ++a) base_.at[static_cast<std::size_t>(a)] = after.position[a];
}

long long ResetRecovery::surely_ran(const PrintHistory& h, long long last_acked, int planner_blocks) const {
  int moves = 0;
  long long n = last_acked;
  while (n > 0) {
    if (n == base_number_) return n;
    // Acknowledged before this session's first line (a resume's handshake):
    // nothing past the base is known to have run.
    if (!h.holds(n)) return n < h.first_held() && base_number_ > 0 ? base_number_ : -1;
    const PrintStep& s = h.step(n);
    // A line of an earlier resume: that resume starts again.
    if (s.restore != 0) return h.holds(s.restore) || s.restore == base_number_ ? s.restore : -1;
    if (s.drains || moves == planner_blocks) return n;
    if (s.move) ++moves;
    n = s.prev;
  }
  return 0;
}

long long ResetRecovery::back_to(const PrintHistory& h, long long last_acked, int planner_blocks,
                                 long long next_number) const {
  long long back = surely_ran(h, last_acked, planner_blocks);
  if (back > 0 && h.held(back).track.top_z <= 0) back = 0;
  if (back == 0 && (h.first_held() != 1 || (next_number > 1 && !h.holds(1)))) back = -1;
  return back;
}

ResetRecovery::Redone ResetRecovery::may_print_twice(const PrintHistory& h, long long last_acked, long long back) {
  Redone r;
  for (long long n = last_acked; n > back; n = h.step(n).prev) {
    const PrintStep& s = h.step(n);
    if (s.restore != 0) continue;
    const MachineState& m = s.after;
    const double z = m.lifted ? m.lift_base_z : m.position[kZ];
    r.z_low = std::min(r.z_low, z);
    r.z_high = std::max(r.z_high, z);
    if (!s.move) continue;
    ++r.moves;
    const std::array<double, 3>& a = h.held(s.prev).at;
    r.mm += std::hypot(s.at[0] - a[0], s.at[1] - a[1], s.at[2] - a[2]);
  }
  return r;
}

ResetResume ResetRecovery::way_back(const PrintStep& t, const Redone& redone) {
  ResetResume way{t.after, t.track.top_z, std::max(redone.z_high, t.after.position[kZ]), t.track.retracted,
                  t.track.retraction};
  // Inside a block of gc-send's own (a pause's): the filament is where the
  // block left it, its way back primes.
  if (t.source_line == 0) way.retracted = way.prime = 0;
  // Where the nozzle stopped is known to be one of those heights only:
  // the highest is taken (too high prints into the air for a layer; too
  // low would push the nozzle into the part).
  if (redone.z_high <= t.after.position[kZ]) way.nozzle_z = std::numeric_limits<double>::quiet_NaN();
  return way;
}

std::vector<long long> ResetRecovery::given_again(const PrintHistory& h, long long newest, long long back,
                                                  bool final_queued) {
  std::vector<long long> again;
  for (long long n = newest; n != back && n > 0; n = h.step(n).prev) {
    const PrintStep& s = h.step(n);
    if (s.restore != 0) continue;
    if (final_queued && n == newest && s.source_line == 0) continue;
    again.push_back(n);
  }
  std::reverse(again.begin(), again.end());
  return again;
}

}  // namespace gcode::serial
