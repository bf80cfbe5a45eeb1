#include "gcode/serial/protocol/in_flight.hpp"

#include <algorithm>

namespace gcode::serial {

InFlight::Answer InFlight::answer_to(const Response& r, bool numbered_oks) const {
  using Kind = Answer::Kind;
  if (entries_.empty()) return {};
  if (r.has_temperature) {
    // The answer to M105 (ours or one in the file): Marlin runs commands in
    // order, so every line sent before it is done. With no M105 in flight it
    // answers a question already written off: it frees nothing.
    auto it = std::find_if(entries_.begin(), entries_.end(), [](const Entry& e) { return e.temperature_query; });
    if (it == entries_.end()) return {};
    // Our own M105s right behind it go too: the answer may be any of
    // theirs (an earlier one's got lost), and a question left behind would
    // wait for an answer already taken.
    auto last = it;
    while (last + 1 != entries_.end() && (last + 1)->own == Own::Question) ++last;
    return {Kind::Through, static_cast<std::size_t>(last - entries_.begin()), static_cast<std::size_t>(last - it)};
  }
  if (numbered_oks) {
    // ADVANCED_OK: "ok N<n>" answers line n, so everything sent before it is
    // done too (an M105 of ours among them lost its answer). An ok without N
    // answers an unnumbered command: our M105 (turned into something else on
    // the way) if it is next, else nothing we know of; taken for it, it
    // frees nothing else (the lines before it have oks with numbers).
    if (r.line >= 0) {
      std::size_t last = entries_.size();
      for (std::size_t i = 0; i < entries_.size(); ++i)
        if (entries_[i].number > 0 && entries_[i].number <= r.line) last = i;
      if (last == entries_.size()) return {};
      return {Kind::Through, last};
    }
    auto it = std::find_if(entries_.begin(), entries_.end(), [](const Entry& e) { return e.own != Own::None; });
    if (it == entries_.end()) return {};
    return {Kind::Question, static_cast<std::size_t>(it - entries_.begin())};
  }
  // A plain ok answers the oldest line. If that is our M105, whose answer
  // carries temperatures, the M105 went wrong on the way (an unknown
  // command) or its answer was lost; either way it is gone, and taking
  // this ok for it frees the least.
  return {Kind::Through, 0};
}

InFlight::Entry InFlight::pop_front() {
  Entry e = entries_.front();
  entries_.pop_front();
  bytes_ -= e.bytes;
  count(e, -1);
  return e;
}

void InFlight::erase(std::size_t index) {
  bytes_ -= entries_[index].bytes;
  count(entries_[index], -1);
  entries_.erase(entries_.begin() + static_cast<std::ptrdiff_t>(index));
}

std::size_t InFlight::drop_from(long long n) {
  auto first = std::find_if(entries_.begin(), entries_.end(), [n](const Entry& e) { return e.number >= n; });
  std::size_t stale = 0;
  for (auto it = first; it != entries_.end(); ++it) {
    stale += it->bytes;
    count(*it, -1);
  }
  bytes_ -= stale;
  entries_.erase(first, entries_.end());
  return stale;
}

void InFlight::count(const Entry& e, int sign) {
  auto add = [sign](std::size_t& n) { n = sign > 0 ? n + 1 : n - 1; };
  if (e.own == Own::Question) add(counts_.questions);
  if (e.own == Own::PaceProbe) add(counts_.probes);
  for (std::size_t bit = 0; bit < kMarks; ++bit)
    if (e.marks & (1u << bit)) add(marked_[bit]);
}

}  // namespace gcode::serial
