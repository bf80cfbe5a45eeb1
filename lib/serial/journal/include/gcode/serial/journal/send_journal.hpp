#pragma once
// gc-send's journal while it prints: what the session and the sender tell it,
// turned into journal records (journal.hpp). The sender's numbering hook
// gives each command's number, input line, layer and the machine state after
// it; the session says where each input line ends (its byte offset), when a layer
// begins (a sync), checkpoints of the hash of the input fed, and what the control changed live (speed, pause state, a
// swapped-in file). Acknowledgements are written once per turn of the loop,
// the newest only: one `A` record a turn instead of one per `ok`.
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "gcode/core/machine_state.hpp"
#include "gcode/serial/journal/input_identity.hpp"
#include "gcode/serial/journal/journal.hpp"
#include "gcode/serial/protocol/numbered_command.hpp"
#include "gcode/serial/protocol/reset_sequence.hpp"

namespace gcode::serial {

// What the print control changed while the print ran (journal fields
// state, paused, swap, swapline, and one per verb the journal keeps).
struct LiveControl {
  // (field, value) of each control verb the journal keeps (control_verbs.hpp:
  // `speed F` as "speed").
  std::vector<std::pair<std::string_view, std::string>> kept;
  std::string_view state;        // PrintControl::state_label(): printing, pausing, paused ...
  bool paused = false;           // a pause block went out: a resume goes back into the pause
  std::string swap;              // the swapped-in file ("" none)
  std::uint64_t swap_line = 0;   // input lines printed before it joined
};

class SendJournal {
 public:
  // `carried`: a resume's commands from the old journal, up to the one that
  // ran last, whose point the journal goes on from (JournalWriter).
  SendJournal(JournalOptions options, const InputIdentity& input, std::string_view port,
              std::vector<JournalEntry> carried = {});

  // The hash of the input's first `bytes` (a checkpoint; the session hashes
  // what it feeds): the records from now on carry it.
  void checkpoint(std::uint64_t bytes, std::uint64_t hash);
  // Input line `line` ends at byte `end` (called as it reaches the control).
  void line_end(std::uint64_t line, std::uint64_t end);
  void layer_began();
  void live(const LiveControl& live) { live_ = live; }

  // The sender's hooks. A command's track and restore are what a resume
  // after a reset needs (the fields top, retr, prime, restore and drained);
  // `closing` marks the closing M400 (field end), after which nothing of
  // the input is left.
  void numbered(const NumberedCommand& command);
  void acknowledged(long long n) { acked_ = n; }

  void flush(double now);
  double next_sync(double now) const { return now + options_sync_; }
  void finish(double now);

  const JournalWriter& writer() const { return writer_; }

 private:
  std::uint64_t offset_of(std::uint64_t line) const;

  JournalWriter writer_;
  double options_sync_;
  std::uint64_t checkpoint_at_ = 0;  // bytes hashed at the newest checkpoint
  std::string checkpoint_;           // its digest
  std::deque<std::pair<std::uint64_t, std::uint64_t>> ends_;  // (input line, end offset), oldest first
  std::uint64_t last_line_ = 0;
  std::uint64_t last_off_ = 0;
  LiveControl live_;
  JournalFields point_;
  // The state point_'s machine fields hold (none for a resume's carried
  // point: the next command writes them all).
  std::optional<MachineState> written_;
  long long acked_ = 0;
  long long acked_written_ = 0;
};

}  // namespace gcode::serial
