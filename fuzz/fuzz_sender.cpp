// libFuzzer target: the printer-reply parser and the sender's state machine
// (gcode/serial/protocol/protocol.hpp, sender.hpp) on arbitrary printer behaviour.
//
// The first bytes pick a configuration (flow mode, queue, buffer, line limit,
// handshake, how many commands and which are junk or over-long); the rest is
// a script of events: reply lines (templates a Marlin printer sends: ok,
// ok N.. P.. B.., ok T:, Resend: for lines in flight, never sent or long
// acknowledged, Error:, busy:, wait, start, action lines, and raw bytes:
// partial lines, binary junk, very long lines), time passing, the timer
// firing, partial writes, Ctrl-C and M112. Everything the sender writes is
// checked as it goes out:
//  * only lines the firmware can read: M110 N0, M115, M105, M112, or a
//    numbered line with a correct checksum, no control byte, backslash or
//    broken UTF-8, within the line limit;
//  * a line number always carries the same command;
//  * no line is skipped: a line goes out for the first time only right after
//    the one before it, after a resend the line asked for goes out first,
//    and a finished print sent every line;
//  * no line is sent twice unless the printer asked: a line goes out again
//    only after a "Resend:" for it or an earlier line came in;
//  * while lines are in flight the sender always has a timer running, and a
//    timer that ran is not due again at once (the event loop would spin).
// Any violation aborts, which libFuzzer reports as a crash; ASan and UBSan
// catch the rest.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/serial/protocol/line_check.hpp"
#include "gcode/serial/protocol/protocol.hpp"
#include "gcode/serial/sender/sender.hpp"

namespace {

using namespace gcode::serial;

[[noreturn]] void fail(const char* what, std::string_view detail = {}) {
  std::fprintf(stderr, "fuzz_sender: %s: %.*s\n", what, static_cast<int>(detail.size()), detail.data());
  std::abort();
}

void check(bool ok, const char* what, std::string_view detail = {}) {
  if (!ok) fail(what, detail);
}

class Script {
 public:
  Script(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  bool done() const { return pos_ >= size_; }
  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  std::string_view bytes(std::size_t n) {
    n = std::min(n, size_ - std::min(pos_, size_));
    std::string_view s(reinterpret_cast<const char*>(data_) + pos_, n);
    pos_ += n;
    return s;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

// Watches the sender's output and the printer's requests.
class Referee {
 public:
  explicit Referee(const Sender& sender) : sender_(sender) {}

  // A "Resend: n" the sender was given.
  void requested(long long n) {
    ++requests_;
    if (n >= 1) lowest_since_.push_back({requests_, n});
  }

  // The sender acted on "Resend: n": the next numbered line must be n.
  void rewound(long long n) { rewound_to_ = n; }

  void line_out(std::string_view line) {
    // Control bytes, backslashes and bytes that are not UTF-8 text.
    check(check_line(line, 0, line.size() + 64).problem != LineProblem::Unreadable,
          "a byte the firmware cannot read went out", line);
    if (line.empty() || line == "M110 N0" || line == "M115" || line == "M105" || line == "M112") return;
    // The handshake again after a printer reset (its greeting came):
    // numbered on from the highest number used, which the restarted printer
    // now expects next; what it had asked for before is forgotten.
    if (line.size() > 6 && line.substr(0, 6) == "M110 N" &&
        line.find_first_not_of("0123456789", 6) == std::string_view::npos) {
      highest_ = std::atoll(std::string(line.substr(6)).c_str());
      rewound_to_ = 0;
      return;
    }
    check(line[0] == 'N', "an unexpected unnumbered line went out", line);
    std::size_t star = line.rfind('*');
    check(star != std::string_view::npos, "a numbered line without checksum", line);
    long long sum = std::atoll(std::string(line.substr(star + 1)).c_str());
    check(sum == checksum(line.substr(0, star)), "a wrong checksum", line);
    check(line.size() + 1 <= sender_.max_line(), "a line longer than the firmware keeps",
          std::string(line) + " (limit " + std::to_string(sender_.max_line()) + ", resets " +
              std::to_string(sender_.stats().resets) + ")");
    long long n = std::atoll(std::string(line.substr(1)).c_str());
    std::size_t space = line.find(' ');
    check(space != std::string_view::npos && space < star, "a numbered line without command", line);
    std::string command(line.substr(space + 1, star - space - 1));
    // After a printer reset the lines it may have lost go out again under
    // new numbers: the order is judged by the tool tests' executed logs
    // (tests/support/reset_check.hpp), not here.
    if (sender_.stats().resets > 0) {
      highest_ = std::max(highest_, n);
      return;
    }
    if (rewound_to_ > 0) {
      check(n == rewound_to_, "after a resend request the line asked for did not go out first", line);
      rewound_to_ = 0;
    }
    auto it = sent_.find(n);
    if (it == sent_.end()) {
      check(n == highest_ + 1, "a line went out before the one before it (skipped)", line);
      highest_ = n;
      sent_[n] = {command, requests_};
      if (is_own(command)) ++own_;
      return;
    }
    // Sent again: only after the printer asked for it or an earlier line.
    bool asked = false;
    for (const auto& [when, m] : lowest_since_) asked = asked || (when > it->second.requests_seen && m <= n);
    check(asked, "a line went out again although the printer did not ask", line);
    // After a rewind gc-send's own question or pace probe may take the number
    // asked for, and the commands from there move up one: a number the printer
    // refused may come back with another command. Whether the printer then
    // ran every command once, in order, the tool tests' executed logs judge.
    if (is_own(command) && it->second.command != command) ++own_;
    it->second.command = command;
    it->second.requests_seen = requests_;
  }

  long long highest() const { return highest_; }
  // Numbered lines that read as gc-send's own (a question, a pace probe):
  // each takes a number of the print's. (A bare G1 of the input's counts
  // too: the check allows up to this many numbers more than lines.)
  long long own() const { return own_; }

 private:
  struct Sent {
    std::string command;
    std::uint64_t requests_seen;  // requests received when it last went out
  };
  const Sender& sender_;
  std::map<long long, Sent> sent_;
  long long highest_ = 0;
  long long rewound_to_ = 0;
  long long own_ = 0;
  static bool is_own(std::string_view command) { return command == "M105" || command == "G1"; }
  std::uint64_t requests_ = 0;
  std::vector<std::pair<std::uint64_t, long long>> lowest_since_;
};

std::string command_for(std::size_t i, Script& s, std::uint8_t kinds) {
  switch ((i * 7 + kinds) % 13) {
    case 0: return "M105";
    case 1: return "G28";
    case 2: return "M117 " + std::string(20 + (kinds % 150), 'm');  // often too long: shortened
    case 3: return "M109 S200";
    case 4: {
      // Bytes from the script: binary junk, control bytes, a backslash...
      std::string junk(s.bytes(1 + kinds % 12));
      return junk.empty() ? std::string("G92 E0") : "G1 X" + junk;
    }
    case 5: return "G1 X1 Y2 " + std::string(kinds, '0');  // over-long for a small limit
    case 6: return "M400";
    default: return "G1 X" + std::to_string(i) + ".5 Y" + std::to_string(i % 17) + " E0.1 F6000";
  }
}

// A reply line: a Marlin-like template or raw bytes from the script.
std::string reply(Script& s, const Sender& sender, long long highest) {
  std::uint8_t kind = s.byte();
  long long n = highest - static_cast<long long>(s.byte() % 8) + 1;
  switch (kind % 20) {
    case 0: case 1: case 2: case 3: case 4: return "ok";
    case 5: return "ok T:20.0 /0.0 B:20.0 /0.0 @:0 B@:0";
    case 6: return "ok N" + std::to_string(n) + " P" + std::to_string(s.byte() % 17) + " B" + std::to_string(s.byte() % 5);
    case 7: return "Resend: " + std::to_string(n);
    case 8: return "Resend: " + std::to_string(s.byte());  // long acknowledged, or never sent
    case 9: return "Error:checksum mismatch, Last Line: " + std::to_string(n - 1);
    case 10: return "echo:busy: processing";
    case 11: return "wait";
    case 12: return "T:180.0 /200.0 B:60.0 /60.0 @:127 B@:0 W:?";
    case 13: return std::string(s.bytes(s.byte()));  // partial line, junk
    case 14: return std::string(2000 + s.byte() * 50, 'o');  // a very long line
    case 15: return "Cap:MAX_CMD_SIZE:" + std::to_string(s.byte());
    case 16: return "//action:" + std::string(s.byte() % 2 ? "pause" : "resume");
    case 17: return sender.state() == SenderState::Printing && s.byte() % 16 == 0 ? "start" : "echo:hello";
    case 18: return "rs " + std::to_string(n);
    default: return "ok P" + std::to_string(s.byte() % 17) + " B3";
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Script s(data, size);
  SenderConfig config;
  config.flow = static_cast<FlowMode>(s.byte() % 4);
  config.queue = 1 + s.byte() % 8;
  config.rx_buffer = 32 + s.byte() % 200;
  config.max_line = 16 + s.byte() % 200;
  std::uint8_t flags = s.byte();
  config.skip_bad_lines = flags & 1;
  config.handshake = flags & 2;
  config.max_line_from_firmware = flags & 4;
  config.link_bytes_per_second = (flags & 8) ? 0 : 25000;
  config.timeout = 1 + s.byte() % 10;
  config.max_timeouts = s.byte() % 6;
  std::size_t commands = 1 + s.byte() % 48;
  std::uint8_t kinds = s.byte();

  // FUZZ_TRACE=1 shows both sides when replaying a crash.
  static const bool trace = std::getenv("FUZZ_TRACE") != nullptr;
  Sender sender(config, trace ? Sender::Logger([](LogLevel, std::uint64_t, std::string_view m) {
    std::fprintf(stderr, "%.*s\n", static_cast<int>(m.size()), m.data());
  })
                              : Sender::Logger());
  sender.set_trace(trace);
  Referee referee(sender);
  double now = 0;
  // The referee sees a line when the sender puts it out, written or not (a
  // request may come in before the port took all of it): `tail` holds the
  // written bytes of a line not seen yet, `ahead` the bytes at the start of
  // the sender's output already seen.
  std::string tail;
  std::size_t ahead = 0;
  std::uint64_t discards = 0;
  auto referee_sees = [&]() {
    // A printer reset throws away what was not yet written (the restarted
    // printer never gets it): nothing seen is left in the output, and a line
    // cut off is a fragment the sender ends with a newline of its own.
    if (sender.output_discards() != discards) {
      discards = sender.output_discards();
      ahead = 0;
      tail.clear();
    }
    std::string stream = tail + std::string(sender.output().substr(ahead));
    std::size_t pos = 0;
    for (std::size_t nl; (nl = stream.find('\n', pos)) != std::string::npos; pos = nl + 1)
      referee.line_out(std::string_view(stream).substr(pos, nl - pos));
    if (pos >= tail.size()) {
      ahead += pos - tail.size();
      tail.clear();
    } else {
      tail.erase(0, pos);
    }
  };
  auto drain = [&](std::size_t limit) {
    referee_sees();
    std::string_view out = sender.output();
    std::size_t n = std::min(out.size(), limit);
    if (n <= ahead) {
      ahead -= n;
    } else {
      tail.append(out.substr(ahead, n - ahead));
      ahead = 0;
    }
    sender.written(n, now);
  };
  std::size_t next = 0;
  sender.start(now);
  // Once the script is over, time goes on for a while: timeouts, the end.
  int after_script = 200;
  for (int events = 0; events < 4000 && !sender.finished() && after_script > 0; ++events) {
    if (s.done()) --after_script;
    while (sender.wants_input() && next < commands) {
      std::string c = command_for(next, s, kinds);
      sender.submit(command_for_sending(c), next + 1, 1);
      ++next;
    }
    if (next == commands && sender.wants_input()) sender.end_of_input();
    sender.pump(now);
    std::uint8_t op = s.done() ? 1 : s.byte();
    switch (op % 16) {
      case 0: drain(s.byte()); break;  // a partial write
      case 1: case 2: {
        // Time passes up to the sender's deadline or a little.
        double d = sender.deadline();
        now = d < 1e299 && d > now ? d : now + 0.001 * (1 + s.byte());
        referee_sees();
        sender.on_timer(now);
        // The event loop sleeps until the deadline: one still due after the
        // timer ran (and the output was written) would spin it.
        drain(static_cast<std::size_t>(-1));
        sender.pump(now);
        drain(static_cast<std::size_t>(-1));
        if (!sender.finished()) check(sender.deadline() > now, "the timer is still due after it ran", std::to_string(now) + " " + std::to_string(sender.deadline()) + " in flight " + std::to_string(sender.in_flight()));
        break;
      }
      case 3: now += 0.0001 * s.byte(); break;
      case 4:
        if (s.byte() == 0) sender.cancel();
        break;
      case 5:
        if (s.byte() == 0) {
          // M112 goes out at once, after a newline that ends a line cut
          // short (the firmware drops it: no checksum); what the port had
          // not taken is dropped.
          sender.emergency_stop();
          tail.clear();
          ahead = 0;
        }
        break;
      default: {
        std::string line = reply(s, sender, referee.highest());
        // The parser must never fail and keep its fields sane.
        Response r = parse_response(line);
        check(r.kind != ResponseKind::Resend || r.line >= 0, "Resend without a line number", line);
        referee_sees();  // what went out before the answer came
        if (r.kind == ResponseKind::Resend) referee.requested(r.line);
        std::uint64_t rewinds = sender.stats().resend_requests;
        sender.on_line(line, now);
        if (sender.stats().resend_requests != rewinds) referee.rewound(r.line);
        break;
      }
    }
    drain(static_cast<std::size_t>(-1));
    if (!sender.finished() && sender.in_flight() > 0 && sender.state() == SenderState::Printing)
      check(sender.deadline() < 1e299, "lines in flight and no timer running");
  }
  drain(static_cast<std::size_t>(-1));
  // (After a printer reset the lines it may have lost go out again with new
  // numbers: more numbers than lines.)
  if (sender.state() == SenderState::Done) {
    const auto lines = static_cast<long long>(sender.stats().lines);
    const bool reset = sender.stats().resets > 0;
    check(reset ? referee.highest() >= lines : (referee.highest() >= lines && referee.highest() <= lines + referee.own()),
          "a finished print did not send every line",
          std::to_string(referee.highest()) + " numbers, " + std::to_string(lines) + " lines, " +
              std::to_string(sender.stats().resets) + " resets");
  }
  return 0;
}
