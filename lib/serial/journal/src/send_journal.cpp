#include "gcode/serial/journal/send_journal.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "gcode/serial/journal/journal_header.hpp"
#include "gcode/serial/journal/journal_point.hpp"

namespace gcode::serial {

namespace {

// Input lines whose end offset is kept: more than the pipeline holds back
// plus what a pause holds (their records are written when they are sent).
constexpr std::size_t kEndsKept = 8192;

}  // namespace

SendJournal::SendJournal(JournalOptions options, const InputIdentity& input, std::string_view port,
                         std::vector<JournalEntry> carried)
    : writer_(options, journal_header(input, port), std::move(carried)), options_sync_(options.sync_interval) {
  checkpoint_ = hash_text(PrefixHash().digest());
  const JournalFields* carried_last = writer_.last_point();
  if (carried_last == nullptr) return;
  // Go on from the point of the command that ran last, already written.
  point_ = *carried_last;
  last_line_ = point_.count("line");
  last_off_ = point_.count("off");
  acked_ = acked_written_ = static_cast<long long>(writer_.acknowledged_line());
}

void SendJournal::checkpoint(std::uint64_t bytes, std::uint64_t hash) {
  checkpoint_at_ = bytes;
  checkpoint_ = hash_text(hash);
}

void SendJournal::line_end(std::uint64_t line, std::uint64_t end) {
  if (!ends_.empty() && line <= ends_.back().first) return;
  ends_.emplace_back(line, end);
  if (ends_.size() > kEndsKept) ends_.pop_front();
}

void SendJournal::layer_began() { writer_.sync_soon(); }

std::uint64_t SendJournal::offset_of(std::uint64_t line) const {
  auto it = std::lower_bound(ends_.begin(), ends_.end(), line,
                             [](const auto& e, std::uint64_t l) { return e.first < l; });
  if (it != ends_.end() && it->first == line) return it->second;
  return last_off_;
}

void SendJournal::numbered(const NumberedCommand& c) {
  if (c.repeat && written_) {
    // gc-send's question or pace probe: where the command before it left
    // the print ("ask" tells it from a command).
    point_.set("ask", "1");
    writer_.sent(static_cast<std::uint64_t>(c.n), point_);
    return;
  }
  point_.set("ask", "0");
  // Commands of the control's own (a pause block, a cancel's end) carry no
  // input line: they keep the position in the input of the line before.
  if (c.source_line != 0) {
    last_off_ = offset_of(c.source_line);
    last_line_ = c.source_line;
  }
  point_.set("line", std::to_string(last_line_));
  point_.set("off", std::to_string(last_off_));
  point_.set("layer", std::to_string(c.layer));
  point_.set("own", c.source_line == 0 ? "1" : "0");
  point_.set("end", c.closing ? "1" : "0");
  write_machine_fields(*c.after, point_, written_ ? &*written_ : nullptr);
  written_ = *c.after;
  point_.set("hash", checkpoint_);
  point_.set("hoff", std::to_string(checkpoint_at_));
  for (const auto& [field, value] : live_.kept) point_.set(field, value);
  point_.set("state", std::string(live_.state));
  point_.set("paused", live_.paused ? "1" : "0");
  point_.set("swap", live_.swap);
  point_.set("swapline", std::to_string(live_.swap_line));
  write_track_fields(*c.track, c.restore, c.drains, point_);
  writer_.sent(static_cast<std::uint64_t>(c.n), point_);
}

void SendJournal::flush(double now) {
  if (acked_ > acked_written_) {
    writer_.acknowledged(static_cast<std::uint64_t>(acked_));
    acked_written_ = acked_;
  }
  writer_.flush(now);
}

void SendJournal::finish(double now) {
  flush(now);
  writer_.finish(now);
}

}  // namespace gcode::serial
