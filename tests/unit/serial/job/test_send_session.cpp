// gc-send's loop (serial/send_session.hpp) against the virtual printer on a
// socketpair: every command of the file reaches the printer once, in order,
// without comments; host commands, M110 and comment lines stay behind;
// layers are counted; Ctrl-C cancels (a safe end), twice sends M112.
#include <catch2/catch.hpp>

#include <sys/socket.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "gcode/serial/job/send_session.hpp"
#include "gcode/serial/sim/virtual_link.hpp"
#include "capture.hpp"
#include "serial_check.hpp"

using namespace gcode::serial;

namespace {

struct Sent {
  SenderState state = SenderState::Idle;
  std::string failure;
  VirtualPrinterStats printer;
  bool halted = false;
  gctest::ExecutedLog log;
  std::uint64_t input_lines = 0, host_commands = 0;
  int layers = 0;
  std::string err;
  std::string unread;  // sent but not yet read by the model when the loop ended
};

// Sends `text` (from a file) to a virtual printer; `at_start` may add to the loop.
Sent send(const std::string& text, VirtualPrinterConfig pc,
          const std::function<void(EventLoop&, const VirtualPrinter&)>& at_start = {}) {
  std::string path = gctest::temp_dir() + "/print.gcode";
  gctest::write_file(path, text);
  gctest::OpenedFile input(path);
  int fds[2];
  REQUIRE(::socketpair(AF_UNIX, SOCK_STREAM, 0, fds) == 0);
  char* log_text = nullptr;
  std::size_t log_size = 0;
  std::FILE* log = open_memstream(&log_text, &log_size);
  Sent r;
  r.err = gctest::stderr_of([&] {
    EventLoop loop;
    VirtualPrinter printer(pc, log);
    VirtualLink link(loop, printer, fds[1]);
    SenderConfig sc;
    sc.link_bytes_per_second = pc.baud / 10 * pc.time_scale;
    sc.time_scale = pc.time_scale;
    Sender sender(sc, [](LogLevel, std::uint64_t, std::string_view) {});
    gcode::Diagnostics diag("gc-send", 0);
    SendSession session(loop, sender, input.fd(), fds[0], diag);
    if (at_start) at_start(loop, printer);
    session.run();
    r.state = sender.state();
    r.failure = sender.failure();
    r.printer = printer.stats();
    r.halted = printer.halted();
    r.input_lines = session.input_lines();
    r.host_commands = session.control() != nullptr ? session.control()->host_commands() : 0;
    r.layers = session.layers();
    char b[4096];
    for (ssize_t n; (n = ::read(fds[1], b, sizeof b)) > 0;) r.unread.append(b, static_cast<std::size_t>(n));
  });
  std::fclose(log);
  r.log = gctest::parse_executed_log(std::string_view(log_text, log_size));
  std::free(log_text);
  ::close(fds[0]);
  ::close(fds[1]);
  return r;
}

VirtualPrinterConfig fast() {
  VirtualPrinterConfig c;
  c.time_scale = 50;
  c.instant_moves = true;
  return c;
}

}  // namespace

TEST_CASE("send session: every command once, in order, nothing else", "[serial][send_session]") {
  const std::string text =
      "; sliced by hand\n"
      "G28 ; home\n"
      "M110 N5\n"
      "@notify done\n"  // a host command (@pause would hold the print: test_gc_send_pause)

      "G1 X10 (a note) Y5 F3000\n"
      "\n"
      ";LAYER:0\nG1 Z0.2\nG1 X20 Y5 E1\n"
      ";LAYER:1\nG1 Z0.4\nG1 X20 Y20 E2\n"
      "M84";  // no final newline
  Sent r = send(text, fast());
  CHECK(r.state == SenderState::Done);
  CHECK(r.failure.empty());
  CHECK(r.input_lines == 13);
  CHECK(r.host_commands == 1);
  CHECK(r.layers == 2);
  CHECK(r.err == "gc-send: line 3: warning: M110 not sent: gc-send numbers the lines itself\n");
  std::vector<std::string> expected;
  for (const gctest::SentCommand& c : gctest::commands_of(text)) expected.push_back(c.text);
  CHECK(expected == std::vector<std::string>{"G28", "G1 X10 Y5 F3000", "G1 Z0.2", "G1 X20 Y5 E1", "G1 Z0.4",
                                             "G1 X20 Y20 E2", "M84"});
  expected.push_back("M400");  // the sender waits for the moves to end
  gctest::drop_own_lines(r.log, expected);
  CHECK(r.log.commands == expected);
  CHECK(gctest::numbers_rise(r.log.numbers));
  CHECK(r.printer.checksum_errors == 0);
  CHECK(r.printer.line_number_errors == 0);
}

TEST_CASE("send session: a long file through a small window, faults and all", "[serial][send_session]") {
  std::string text = "G28\nG90\n";
  for (int i = 0; i < 3000; ++i) text += "G1 X" + std::to_string(i % 200) + " Y" + std::to_string(i % 7) + " F6000\n";
  VirtualPrinterConfig c = fast();
  c.corrupt = 0.02;
  c.drop_ok = 0.01;
  Sent r = send(text, c);
  CHECK(r.state == SenderState::Done);
  std::vector<std::string> expected;
  for (const gctest::SentCommand& s : gctest::commands_of(text)) expected.push_back(s.text);
  expected.push_back("M400");
  gctest::drop_own_lines(r.log, expected);
  REQUIRE(r.log.commands.size() == 3003);
  CHECK(r.log.commands == expected);
  CHECK(gctest::numbers_rise(r.log.numbers));
  CHECK(r.printer.corrupted > 0);
  CHECK(r.input_lines == 3002);
}

TEST_CASE("send session: Ctrl-C cancels, twice sends M112", "[serial][send_session]") {
  std::string text;
  for (int i = 0; i < 20000; ++i) text += "G1 X" + std::to_string(i % 2 * 10) + " F600\n";  // 1 s per move
  VirtualPrinterConfig slow;
  slow.time_scale = 20;
  // Ctrl-C `count` times once printing is under way, 20 ms apart.
  auto interrupts = [](int count) {
    return [count](EventLoop& loop, const VirtualPrinter& printer) {
      auto fired = std::make_shared<int>(0);
      auto last = std::make_shared<double>(0);
      auto next = std::make_shared<double>(EventLoop::now());
      loop.add_timer([=] { return *fired < count ? *next : 1e300; },
                     [=, &printer](double now) {
                       *next = now + 0.01;
                       if (printer.stats().executed < 5 || (*fired > 0 && now - *last < 0.02)) return;
                       ++*fired;
                       *last = now;
                       std::raise(SIGINT);  // blocked by the session: read from its signalfd
                     });
    };
  };
  Sent once = send(text, slow, interrupts(1));
  // The safe end (here the library's default, with no end script) is printed
  // and acknowledged: the sender is done, and the file's unsent commands did
  // not go before it (fewer than 1000 of 20000 executed, below).
  CHECK(once.state == SenderState::Done);
  REQUIRE(once.log.commands.size() > 2);
  CHECK(once.log.commands.back() == "M400");
  // A first Ctrl-C is a cancel: the safe end (print_control.hpp), not an emergency.
  CHECK(once.err.find("gc-send: interrupted: cancelling (safe end)") != std::string::npos);
  CHECK(once.log.commands.size() > 0);  // printing had begun
  CHECK(once.log.commands.size() < 1000);
  CHECK_FALSE(once.halted);
  Sent twice = send(text, slow, interrupts(2));
  CHECK(twice.err.find("gc-send: emergency stop: M112 sent\n") != std::string::npos);
  // The model shares the session's loop, which ends as soon as M112 is
  // written: it is on the wire, or the model already read it and halted.
  CHECK((twice.halted || twice.unread.find("M112") != std::string::npos));
  CHECK(twice.log.commands.size() < 1000);
}

TEST_CASE("send session: the signal mask is the caller's again afterwards", "[serial][send_session]") {
  auto blocked = [](int sig) {
    sigset_t now;
    sigprocmask(SIG_SETMASK, nullptr, &now);
    return sigismember(&now, sig) == 1;
  };
  REQUIRE_FALSE(blocked(SIGINT));
  send("G28\n", fast());
  CHECK_FALSE(blocked(SIGINT));
  CHECK_FALSE(blocked(SIGTERM));
  // A caller that blocks SIGTERM itself keeps it blocked.
  sigset_t term;
  sigemptyset(&term);
  sigaddset(&term, SIGTERM);
  sigprocmask(SIG_BLOCK, &term, nullptr);
  send("G28\n", fast());
  CHECK(blocked(SIGTERM));
  CHECK_FALSE(blocked(SIGINT));
  sigprocmask(SIG_UNBLOCK, &term, nullptr);
}
