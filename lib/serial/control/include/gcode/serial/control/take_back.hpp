#pragma once
// The take-back ledger of gc-send's print control: the file's commands
// handed to the sender since gc-send's own last lines (a block, a typed
// command), each with the stream's state and pause context before it. The
// newest of them that the sender has not sent yet can be taken back: a
// pause now puts them after its block, a cancel leaves them out, and the
// stream goes on from the state before the first of them.
//
// Two rules keep it honest: what the sender has sent can no longer be taken
// back (keep_unsent), and nothing can be taken back over lines of gc-send's
// own (own_lines), whose effect on the stream the ledger does not know.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include "gcode/core/machine_state.hpp"
#include "gcode/transform/pause_context.hpp"

namespace gcode::serial {

class TakeBackLedger {
 public:
  struct Entry {
    MachineState before;       // the stream before the command
    PauseContext context;      // what was printed before it
    std::uint64_t source = 0;  // its input line
    int layer = 0;
    long long number = 0;      // the number the sender gave it
  };

  // A command of the file went to the sender.
  void handed(Entry entry) { entries_.push_back(std::move(entry)); }
  // The sender still holds `unsent` commands unsent, the newest it was
  // handed: every entry older than those has gone out. (By count, not by
  // number: a line of the sender's own moves unsent numbers up.)
  void keep_unsent(std::size_t unsent);
  // Lines of gc-send's own went to the sender after input line `last_source`.
  void own_lines(std::uint64_t last_source);

  // Whether the newest `n` commands can be taken back, `unsent` being what
  // the sender still holds unsent (the newest commands handed over).
  bool can_take_back(std::size_t n, std::size_t unsent) const {
    return n > 0 && n <= entries_.size() && n <= unsent;
  }
  // Removes the newest `n` (can_take_back): returned oldest first.
  std::vector<Entry> take_back(std::size_t n);

  // Oldest first.
  const std::deque<Entry>& entries() const { return entries_; }
  std::size_t size() const { return entries_.size(); }
  // The input line of the newest command that stays handed over.
  std::uint64_t last_source() const { return entries_.empty() ? sent_source_ : entries_.back().source; }

 private:
  std::deque<Entry> entries_;
  std::uint64_t sent_source_ = 0;  // the input line of the last command before entries_
};

}  // namespace gcode::serial
