// The sender (gcode/serial/sender/sender.hpp) fed with scripted printer answers,
// one line at a time: exactly which lines go out after each answer, and
// exactly when the sender would ask with M105 because an answer is overdue.
//
// The link is a pseudo-terminal's (no byte time), so an answer is due 0.1 s
// (the margin) after the line was written and the answer before it came,
// unless the planner or a keepalive says otherwise.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "gcode/serial/sender/sender.hpp"

using namespace gcode::serial;

namespace {

using Lines = std::vector<std::string>;

constexpr double kMargin = 0.1;

// As the sender writes it, without its newline.
std::string numbered_line(long long n, std::string_view command) {
  std::string s;
  append_numbered_line(s, n, command);
  s.pop_back();
  return s;
}

// Commands without motion: the answer to each is due 0.1 s after it could come.
Lines messages_1_to(int n) {
  Lines c;
  for (int i = 1; i <= n; ++i) c.push_back("M117 " + std::to_string(i));
  return c;
}

// Window flow (BUFSIZE 4, RX 128), no handshake, a link without byte time.
SenderConfig replay_config(FlowMode flow = FlowMode::Window) {
  SenderConfig c;
  c.flow = flow;
  c.handshake = false;
  c.link_bytes_per_second = 0;
  c.timeout = 10;
  return c;
}

struct SenderReplay {
  explicit SenderReplay(const SenderConfig& c = replay_config())
      : sender(c, [this](LogLevel level, std::uint64_t line, std::string_view m) {
          if (level != LogLevel::Trace)
            messages.push_back((line > 0 ? "line " + std::to_string(line) + ": " : "") + std::string(m));
        }) {
    sender.start(0);
  }

  // Queues commands as the input would, up to what the sender takes.
  void input(const Lines& commands, bool end = true) {
    for (const std::string& c : commands) sender.submit(c, ++input_line, 1);
    if (end) sender.end_of_input();
  }
  // What went out since the last call, one entry per line.
  Lines sent() {
    sender.pump(now);
    Lines lines;
    std::string_view out = sender.output();
    std::size_t pos = 0;
    for (std::size_t nl; (nl = out.find('\n', pos)) != std::string_view::npos; pos = nl + 1)
      lines.emplace_back(out.substr(pos, nl - pos));
    sender.written(out.size(), now);
    for (const std::string& l : lines) all_sent.push_back(l);
    return lines;
  }
  void reply(const Lines& answers, double t) {
    now = t;
    for (const std::string& a : answers) sender.on_line(a, now);
  }
  // Runs the timers at `t`.
  void at(double t) {
    now = t;
    sender.on_timer(t);
  }
  // Queues "M117 1" ... "M117 n" and ends the input; returns the commands
  // as they are numbered, the final M400 included.
  Lines input_messages(int n) {
    Lines c = messages_1_to(n);
    input(c);
    c.push_back("M400");
    commands = c;
    return c;
  }
  std::size_t times_sent(const std::string& line) const {
    std::size_t n = 0;
    for (const std::string& l : all_sent) n += l == line;
    return n;
  }
  // How often line `n` of input_messages() went out.
  std::size_t times_sent(long long n) const {
    return times_sent(numbered_line(n, commands[static_cast<std::size_t>(n - 1)]));
  }

  Sender sender;
  double now = 0;
  std::uint64_t input_line = 0;
  Lines all_sent;
  Lines messages;
  Lines commands;
};

Lines numbered_range(long long from, long long to, const Lines& commands) {
  Lines out;
  for (long long n = from; n <= to; ++n) out.push_back(numbered_line(n, commands[static_cast<std::size_t>(n - 1)]));
  return out;
}

}  // namespace

TEST_CASE("replay: a lost ok in window mode is asked for 0.1 s after it was due and M105's answer frees the rest",
          "[serial]") {
  SenderReplay r;
  Lines c = r.input_messages(6);
  CHECK(r.sent() == numbered_range(1, 4, c));  // BUFSIZE 4 in flight
  CHECK(r.sender.deadline() == Approx(kMargin));
  r.reply({"ok"}, 0.01);  // N1
  CHECK(r.sent() == Lines{numbered_line(5, c[4])});
  CHECK(r.sender.deadline() == Approx(0.01 + kMargin));
  // N2's ok is lost: N3's is taken for it, and so on; the sender believes
  // one line more is in flight than there is.
  r.reply({"ok"}, 0.02);
  CHECK(r.sent() == Lines{numbered_line(6, c[5])});
  r.reply({"ok"}, 0.03);
  CHECK(r.sent() == Lines{numbered_line(7, "M400")});
  r.reply({"ok"}, 0.04);
  r.reply({"ok"}, 0.05);
  r.reply({"ok"}, 0.06);  // M400's own ok, taken for N6's
  CHECK(r.sent().empty());
  CHECK(r.sender.in_flight() == 1);
  CHECK(r.sender.state() == SenderState::Printing);
  // M400 waits for the planner, which is empty: due 0.1 s after the last ok.
  CHECK(r.sender.deadline() == Approx(0.06 + kMargin));
  r.at(0.159);
  CHECK(r.sent().empty());
  r.at(0.16);
  CHECK(r.sent() == Lines{numbered_line(8, "M105")});
  CHECK(r.sender.stats().probes == 1);
  CHECK(r.sender.stats().timeouts == 0);
  // Marlin answers M105 in order: everything before it is done.
  r.reply({"ok T:20.00 /0.00 B:20.00 /0.00 @:0 B@:0"}, 0.17);
  CHECK(r.sender.state() == SenderState::Done);
  CHECK(r.sender.stats().stray_oks == 0);
  CHECK(r.sender.last_acknowledged().number == 8);
  for (long long n = 1; n <= 7; ++n) CHECK(r.times_sent(n) == 1);
}

TEST_CASE("replay: an error burst with lines in flight is one rewind and each line goes out again once", "[serial]") {
  SenderReplay r;
  Lines c = r.input_messages(8);
  CHECK(r.sent() == numbered_range(1, 4, c));
  r.reply({"ok"}, 0.01);
  CHECK(r.sent() == Lines{numbered_line(5, c[4])});
  // N2 arrived corrupted; Marlin empties its buffer and asks for 2.
  r.reply({"Error:checksum mismatch, Last Line: 1", "Resend: 2", "ok"}, 0.02);
  CHECK(r.sent().empty());
  CHECK(r.sender.in_flight() == 0);
  // Quiet for 20 ms (the link's speed is unknown) before line 2 goes again.
  CHECK(r.sender.deadline() == Approx(0.04));
  // N3 and N4 were on the wire behind it: each draws its own Error, Resend
  // and ok; N5 was emptied out of the buffer and draws nothing.
  r.reply({"Error:Line Number is not Last Line Number+1, Last Line: 1", "Resend: 2", "ok"}, 0.025);
  r.reply({"Error:Line Number is not Last Line Number+1, Last Line: 1", "Resend: 2", "ok"}, 0.03);
  CHECK(r.sent().empty());
  CHECK(r.sender.deadline() == Approx(0.05));
  r.at(0.049);
  CHECK(r.sent().empty());
  r.at(0.05);
  CHECK(r.sent() == numbered_range(2, 5, c));
  CHECK(r.sender.stats().resend_requests == 1);
  CHECK(r.sender.stats().duplicate_resends == 2);
  CHECK(r.sender.stats().resent_lines == 4);
  // Each ok now frees one line: none of the three oks of the burst freed one.
  r.reply({"ok"}, 0.06);
  CHECK(r.sent() == Lines{numbered_line(6, c[5])});
  r.reply({"ok"}, 0.07);
  r.reply({"ok"}, 0.08);
  r.reply({"ok"}, 0.09);
  CHECK(r.sent() == numbered_range(7, 9, c));
  for (double t : {0.10, 0.11, 0.12, 0.13}) r.reply({"ok"}, t);
  CHECK(r.sender.state() == SenderState::Done);
  CHECK(r.sender.stats().stray_oks == 0);
  CHECK(r.sender.stats().probes == 0);
  for (long long n = 1; n <= 9; ++n) CHECK(r.times_sent(n) == (n >= 2 && n <= 5 ? 2u : 1u));
}

TEST_CASE("replay: a Resend for the line being resent is a repeat until that line has gone out again", "[serial]") {
  SenderReplay r;
  Lines c = r.input_messages(3);
  CHECK(r.sent() == numbered_range(1, 4, c));
  r.reply({"ok", "Error:checksum mismatch, Last Line: 1", "Resend: 2", "ok"}, 0.01);
  r.reply({"Error:Line Number is not Last Line Number+1, Last Line: 1", "Resend: 2", "ok"}, 0.012);
  r.at(0.032);
  CHECK(r.sent() == numbered_range(2, 4, c));
  // Line 2 arrived corrupted again: a new request.
  r.reply({"Error:checksum mismatch, Last Line: 1", "Resend: 2", "ok"}, 0.04);
  CHECK(r.sender.stats().resend_requests == 2);
  CHECK(r.sender.stats().duplicate_resends == 1);
  r.reply({"Error:Line Number is not Last Line Number+1, Last Line: 1", "Resend: 2", "ok"}, 0.041);
  r.reply({"Error:Line Number is not Last Line Number+1, Last Line: 1", "Resend: 2", "ok"}, 0.042);
  CHECK(r.sender.stats().duplicate_resends == 3);
  r.at(0.062);
  CHECK(r.sent() == numbered_range(2, 4, c));
  for (double t : {0.07, 0.08, 0.09}) r.reply({"ok"}, t);
  CHECK(r.sender.state() == SenderState::Done);
  CHECK(r.times_sent(2) == 3);
  CHECK(r.sender.stats().stray_oks == 0);
}

TEST_CASE("replay: Resend for a line never sent and too many requests for one line", "[serial]") {
  SenderReplay r;
  Lines c = r.input_messages(3);
  CHECK(r.sent() == numbered_range(1, 4, c));
  // Nothing to rewind to; the ok after it belongs to the request.
  r.reply({"Resend: 9", "ok"}, 0.01);
  CHECK(r.sender.stats().ignored_resends == 1);
  CHECK(r.sender.in_flight() == 4);
  CHECK(r.sent().empty());
  for (double t : {0.02, 0.03, 0.04, 0.05}) r.reply({"ok"}, t);
  CHECK(r.sender.state() == SenderState::Done);
  CHECK(r.sender.stats().stray_oks == 0);

  SenderConfig config = replay_config();
  config.max_resends = 2;
  SenderReplay s(config);
  s.input({"M117 a"});
  CHECK(s.sent() == Lines{numbered_line(1, "M117 a"), numbered_line(2, "M400")});
  double t = 0;
  for (int round = 0; round < 2; ++round) {
    s.reply({"Error:checksum mismatch, Last Line: 0", "Resend: 1", "ok"}, t += 0.01);
    s.at(t += 0.03);
    CHECK(s.sent() == Lines{numbered_line(1, "M117 a"), numbered_line(2, "M400")});
  }
  s.reply({"Error:checksum mismatch, Last Line: 0", "Resend: 1", "ok"}, t += 0.01);
  CHECK(s.sender.state() == SenderState::Failed);
  CHECK(s.sender.failure() == "the printer asked for line 1 3 times; giving up");
}

TEST_CASE("replay: ADVANCED_OK numbers free every line up to them and a lost ok costs nothing", "[serial]") {
  SenderReplay r(replay_config(FlowMode::AdvancedOk));
  Lines c = r.input_messages(5);
  CHECK(r.sent() == numbered_range(1, 4, c));
  r.reply({"ok N1 P16 B3"}, 0.01);
  CHECK(r.sent() == Lines{numbered_line(5, c[4])});
  // N2's ok is lost; N3's frees both.
  r.reply({"ok N3 P16 B3"}, 0.02);
  CHECK(r.sent() == Lines{numbered_line(6, "M400")});
  CHECK(r.sender.in_flight() == 3);
  // An ok without N answers no numbered line (a rejected line's, or a
  // command that was never ours).
  r.reply({"ok P16 B3"}, 0.03);
  CHECK(r.sender.in_flight() == 3);
  CHECK(r.sender.stats().stray_oks == 1);
  r.reply({"ok N6 P16 B3"}, 0.04);
  CHECK(r.sender.state() == SenderState::Done);
  CHECK(r.sender.stats().stray_oks == 1);
  CHECK(r.sender.stats().probes == 0);
}

TEST_CASE("replay: busy messages keep a G28 waiting: the answer is due 1.5 keepalive intervals after the last",
          "[serial]") {
  SenderReplay r;
  r.input({"G28", "M117 homed"});
  CHECK(r.sent() == Lines{numbered_line(1, "G28"), numbered_line(2, "M117 homed"), numbered_line(3, "M400")});
  // Nothing heard yet: Marlin's 2 s keepalive interval is assumed.
  CHECK(r.sender.deadline() == Approx(3.0 + kMargin));
  r.reply({"echo:busy: processing"}, 2.0);
  CHECK(r.sender.deadline() == Approx(2.0 + 3.0 + kMargin));
  r.reply({"echo:busy: processing"}, 4.0);
  CHECK(r.sender.deadline() == Approx(4.0 + 3.0 + kMargin));
  r.reply({"ok"}, 5.0);
  // Homed: the next line is due 0.1 s after that ok.
  CHECK(r.sender.deadline() == Approx(5.0 + kMargin));
  r.reply({"ok", "ok"}, 5.01);
  CHECK(r.sender.state() == SenderState::Done);
  CHECK(r.sender.stats().probes == 0);
  CHECK(r.sender.stats().busy == 2);
}

TEST_CASE("replay: temperature reports while M109 heats are keepalives and a silent heater is asked once", "[serial]") {
  SenderReplay r;
  r.input({"M109 S200", "G1 X10 F600"});
  CHECK(r.sent() == Lines{numbered_line(1, "M109 S200"), numbered_line(2, "G1 X10 F600"), numbered_line(3, "M400")});
  for (int i = 1; i <= 5; ++i) {
    r.reply({"T:" + std::to_string(20 + 30 * i) + ".00 /200.00 B:20.00 /0.00 @:127 B@:0 W:?"}, i);
    CHECK(r.sent().empty());
  }
  // Reports every second: the next is expected within 1.5 s.
  CHECK(r.sender.deadline() == Approx(5.0 + 1.5 + kMargin));
  r.at(6.6);
  CHECK(r.sent() == Lines{numbered_line(4, "M105")});
  // With M109 still ahead, the sender does not ask again before --timeout
  // (10 s, six times that for a long command) has passed without a sign of life.
  CHECK(r.sender.deadline() == Approx(5.0 + 60));
  r.reply({"ok"}, 7.0);  // M109 done
  CHECK(r.sender.in_flight() == 3);
}

TEST_CASE("replay: a printer that says wait while lines are in flight is asked at once", "[serial]") {
  SenderReplay r;
  r.input({"M117 a"});
  CHECK(r.sent() == Lines{numbered_line(1, "M117 a"), numbered_line(2, "M400")});
  r.reply({"ok"}, 0.01);
  CHECK(r.sender.deadline() == Approx(0.01 + kMargin));
  // N2's ok was lost and the printer is idle.
  r.reply({"wait"}, 0.05);
  CHECK(r.sender.deadline() <= 0.05);
  r.at(0.05);
  CHECK(r.sent() == Lines{numbered_line(3, "M105")});
  r.reply({"ok T:20.0 /0.0 B:20.0 /0.0"}, 0.06);
  CHECK(r.sender.state() == SenderState::Done);
}

TEST_CASE("replay: an M105 whose answer was lost is asked again and a plain ok in its place takes it", "[serial]") {
  SenderReplay r;
  r.input(messages_1_to(1));
  CHECK(r.sent() == Lines{numbered_line(1, "M117 1"), numbered_line(2, "M400")});
  r.at(0.1);
  CHECK(r.sent() == Lines{numbered_line(3, "M105")});
  // The oks of N1 and N2 were only late; the M105's answer is lost. Every
  // line is acknowledged: the print is done, the question no longer matters.
  r.reply({"ok", "ok"}, 0.15);
  CHECK(r.sender.state() == SenderState::Done);
  CHECK(r.sender.stats().stray_oks == 0);

  // Here N2's ok is lost, and the answer to the first M105 too: asked again
  // 0.2 s after it was due (twice the wait of the first question). The
  // answer that comes is taken for the oldest M105's.
  SenderReplay s;
  s.input(messages_1_to(1));
  s.sent();
  s.reply({"ok"}, 0.05);
  CHECK(s.sender.deadline() == Approx(0.05 + kMargin));
  s.at(s.sender.deadline());
  CHECK(s.sent() == Lines{numbered_line(3, "M105")});
  CHECK(s.sender.deadline() == Approx(0.15 + 2 * kMargin));
  s.at(s.sender.deadline());
  CHECK(s.sent() == Lines{numbered_line(4, "M105")});
  CHECK(s.sender.stats().probes == 2);
  s.reply({"ok T:20.0 /0.0 B:20.0 /0.0"}, 0.36);
  CHECK(s.sender.state() == SenderState::Done);

  // A plain ok with our M105 next: the M105 was garbled into an unknown
  // command (which Marlin answers with a plain ok) or its answer was lost.
  // Taking the ok for it frees the least; what it leaves believed in flight
  // is asked for again.
  SenderReplay u;
  Lines c = u.input_messages(5);
  CHECK(u.sent() == numbered_range(1, 4, c));
  u.reply({"ok"}, 0.01);  // N1
  CHECK(u.sent() == Lines{numbered_line(5, c[4])});
  // N2's ok is lost.
  u.at(u.sender.deadline());
  CHECK(u.now == Approx(0.01 + kMargin));
  CHECK(u.sent() == Lines{numbered_line(6, "M105")});
  u.reply({"ok"}, 0.12);  // N3's, taken for N2's
  CHECK(u.sent() == Lines{numbered_line(7, "M400")});
  u.reply({"ok"}, 0.125);  // N4's
  u.reply({"ok", "ok"}, 0.13);  // N5's and the garbled M105's
  CHECK(u.sender.in_flight() == 2);   // the M105 and the M400
  u.reply({"ok"}, 0.14);              // the M400's own, taken for the M105
  CHECK(u.sender.in_flight() == 1);
  CHECK(u.sender.state() == SenderState::Printing);
  u.at(u.sender.deadline());
  CHECK(u.now == Approx(0.14 + kMargin));
  CHECK(u.sent() == Lines{numbered_line(8, "M105")});
  u.reply({"ok T:20.0 /0.0"}, 0.25);
  CHECK(u.sender.state() == SenderState::Done);
  CHECK(u.sender.stats().stray_oks == 0);
  CHECK(u.sender.stats().probes == 2);
}

TEST_CASE("replay: a silent printer is asked again and again and given up after max-timeouts rounds", "[serial]") {
  SenderConfig config = replay_config();
  config.timeout = 1;
  config.max_timeouts = 2;
  SenderReplay r(config);
  r.input({"M117 a"});
  r.sent();
  double t = 0;
  Lines probes;
  while (r.sender.state() == SenderState::Printing && t < 100) {
    t = r.sender.deadline();
    r.at(t);
    for (const std::string& l : r.sent()) probes.push_back(l + " @" + std::to_string(t));
  }
  CHECK(r.sender.state() == SenderState::Failed);
  CHECK(r.sender.failure() == "the printer stopped answering (2 timeouts of 6 s in a row); last acknowledged: none "
                              "(no line was acknowledged)");
  // Three quick questions, from 0.1 s after the answer was due, each
  // waiting twice as long; then one for every --timeout without any sign of
  // life, six times as long while a long command (M400) is in flight.
  CHECK(probes == Lines{numbered_line(3, "M105") + " @0.100000", numbered_line(4, "M105") + " @0.300000", numbered_line(5, "M105") + " @0.700000",
                        numbered_line(6, "M105") + " @6.000000", numbered_line(7, "M105") + " @12.000000"});
  CHECK(t == Approx(18.0));
  CHECK(r.sender.stats().timeouts == 3);
  CHECK(r.sender.stats().probes == 3);
}

TEST_CASE("replay: an over-long M117 goes out shortened with a warning naming its input line", "[serial]") {
  SenderReplay r;
  std::string long_message = "M117 " + std::string(150, 'x');
  r.input({"G92 E0", long_message});
  Lines sent = r.sent();
  // (M400 waits: with them and room for a numbered M105 it would not fit
  // into the printer's 128 bytes.)
  REQUIRE(sent.size() == 2);
  // "N2 " + 88 bytes of command + "*" + the checksum's three digits at most.
  CHECK(sent[1] == numbered_line(2, "M117 " + std::string(83, 'x')));
  CHECK(sent[1].size() == 95);
  REQUIRE(r.messages.size() == 1);
  CHECK(r.messages[0].rfind("line 2: M117 message shortened to 88 bytes", 0) == 0);
  CHECK(r.sender.stats().shortened == 1);
}

TEST_CASE("replay: a line the firmware cannot take stops the print before it once the lines before it are done", "[serial]") {
  SenderReplay r;
  std::string g1 = "G1 X1 Y2 E3" + std::string(120, '0');
  r.input({"M117 a", "M117 b", g1, "M117 never"}, false);
  // Nothing more is read once the line is refused.
  CHECK_FALSE(r.sender.wants_input());
  CHECK(r.sent() == Lines{numbered_line(1, "M117 a"), numbered_line(2, "M117 b"), numbered_line(3, "M400")});
  for (double t : {0.01, 0.02, 0.03}) r.reply({"ok"}, t);
  CHECK(r.sender.state() == SenderState::Failed);
  CHECK(r.sender.failure() ==
        "line 3: the line is 138 bytes with its line number and checksum; the printer keeps 95 (--max-line 96) and "
        "would refuse it every time it is sent; not sent: printing stopped before it (--skip-bad-lines leaves such "
        "lines out)");
  CHECK(r.times_sent(numbered_line(3, g1)) == 0);
  // Refused at the first line: nothing to print, it fails at once.
  SenderReplay s;
  s.input({"\x89PNG", "G28"}, false);
  CHECK(s.sender.state() == SenderState::Failed);
  CHECK(s.sender.failure().rfind("line 1: byte 0x89 at column 1 is not G-code text", 0) == 0);
  CHECK(s.sent().empty());
}

TEST_CASE("replay: skip-bad-lines leaves out binary junk and over-long lines and goes on", "[serial]") {
  SenderConfig config = replay_config();
  config.skip_bad_lines = true;
  SenderReplay r(config);
  r.input({"M117 a", std::string("G1 X\x01\x02\xff", 7), "G1 X1" + std::string(100, '0'), "M117 b"});
  CHECK(r.sent() == Lines{numbered_line(1, "M117 a"), numbered_line(2, "M117 b"), numbered_line(3, "M400")});
  CHECK(r.messages == Lines{"line 2: byte 0x01 at column 5 is not G-code text (a control byte or binary data); left "
                            "out (--skip-bad-lines)",
                            "line 3: the line is 111 bytes with its line number and checksum; the printer keeps 95 "
                            "(--max-line 96) and would refuse it every time it is sent; left out (--skip-bad-lines)"});
  for (double t : {0.01, 0.02, 0.03}) r.reply({"ok"}, t);
  CHECK(r.sender.state() == SenderState::Done);
  CHECK(r.sender.stats().skipped == 2);
}

TEST_CASE("replay: an input without a command prints nothing and fails", "[serial]") {
  SenderReplay r;
  r.input({});
  CHECK(r.sender.state() == SenderState::Failed);
  CHECK(r.sender.failure() == "nothing was printed: the input has no G-code command");
  CHECK(r.sent().empty());
  SenderConfig config = replay_config();
  config.skip_bad_lines = true;
  SenderReplay s(config);
  s.input({"\x7f\x45\x4c\x46"});
  CHECK(s.sender.state() == SenderState::Failed);
  CHECK(s.sender.failure() == "nothing was printed: all 1 commands of the input were left out");
}

TEST_CASE("replay: the handshake comes first and MAX_CMD_SIZE from M115 sets the line limit", "[serial]") {
  SenderConfig config = replay_config();
  config.handshake = true;
  SenderReplay r(config);
  CHECK_FALSE(r.sender.wants_input());
  CHECK(r.sent() == Lines{"M110 N0"});
  r.reply({"ok"}, 0.01);
  CHECK(r.sent() == Lines{"M115"});
  r.reply({"FIRMWARE_NAME:Marlin 2.1.2 (test) SOURCE_CODE_URL:x PROTOCOL_VERSION:1.0", "Cap:MAX_CMD_SIZE:40", "ok"},
          0.02);
  CHECK_FALSE(r.sender.wants_input());
  r.at(0.07);  // the link has been quiet for 50 ms: printing starts
  CHECK(r.sender.wants_input());
  CHECK(r.sender.max_line() == 40);
  r.input({"M117 " + std::string(50, 'y')});
  Lines sent = r.sent();
  REQUIRE(sent.size() == 2);
  CHECK(sent[0] == numbered_line(1, "M117 " + std::string(27, 'y')));  // 39 bytes
  // An explicit --max-line wins over the firmware's report.
  config.max_line_from_firmware = false;
  SenderReplay s(config);
  s.sent();
  s.reply({"ok"}, 0.01);
  s.reply({"Cap:MAX_CMD_SIZE:40", "ok"}, 0.02);
  s.at(0.07);
  CHECK(s.sender.max_line() == 96);
}

TEST_CASE("replay: a line that lost its N on the way is resent and not counted as a command the firmware refused",
          "[serial]") {
  // Real Marlin: "N2 M117 2*.." arrived as "2 M117 2*..": it answers the
  // unknown command with its ok, then refuses N3 (it expects 2) and asks
  // for 2 again.
  SenderReplay r;
  Lines c = r.input_messages(3);
  CHECK(r.sent() == numbered_range(1, 4, c));
  r.reply({"ok", "echo:Unknown command: \"2 M117 2*18\"", "ok",
           "Error:Line Number is not Last Line Number+1, Last Line: 1", "Resend: 2", "ok"},
          0.01);
  r.at(0.2);
  r.sent();
  for (double t = 0.3; t < 2 && r.sender.state() == SenderState::Printing; t += 0.1) {
    r.reply({"ok"}, t);
    r.sent();
  }
  CHECK(r.sender.state() == SenderState::Done);
  CHECK(r.sender.stats().unknown_commands == 0);
  CHECK(r.times_sent(2) == 2);
}
