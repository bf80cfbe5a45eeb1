#include "gcode/serial/control/take_back.hpp"

#include <iterator>

namespace gcode::serial {

void TakeBackLedger::keep_unsent(std::size_t unsent) {
  while (entries_.size() > unsent) {
    sent_source_ = entries_.front().source;
    entries_.pop_front();
  }
}

void TakeBackLedger::own_lines(std::uint64_t last_source) {
  entries_.clear();
  sent_source_ = last_source;
}

std::vector<TakeBackLedger::Entry> TakeBackLedger::take_back(std::size_t n) {
  const auto from = entries_.end() - static_cast<std::ptrdiff_t>(n);
  std::vector<Entry> out(std::make_move_iterator(from), std::make_move_iterator(entries_.end()));
  entries_.erase(from, entries_.end());
  return out;
}

}  // namespace gcode::serial
