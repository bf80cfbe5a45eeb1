// The handshake's rules (handshake.hpp), on their own and as the sender
// applies them: M110 names the number the print goes on from, M115 follows
// M110's ok, each is asked again on a timer, and a firmware that answers
// M110 but never M115 is printed to without its capabilities.
#include <catch2/catch.hpp>

#include <string>

#include "gcode/serial/sender/handshake.hpp"
#include "gcode/serial/sender/sender.hpp"

using namespace gcode::serial;

TEST_CASE("handshake: M110 names the number the print goes on from", "[serial][handshake]") {
  Handshake h(10);
  CHECK(h.begin(0) == "M110 N0");
  CHECK(h.step() == Handshake::Step::Numbering);
  // After a reset: the last number that went out.
  h.number_on_from(3380);
  CHECK(h.question() == "M110 N3380");
  CHECK(h.begin(5) == "M110 N3380");
}

TEST_CASE("handshake: M115 goes out after M110's ok, its first ok carries the capabilities",
          "[serial][handshake]") {
  Handshake h(10);
  h.begin(0);
  CHECK(h.ok(0.1) == Handshake::Answer::AskCapabilities);
  CHECK(h.step() == Handshake::Step::Capabilities);
  CHECK(h.question() == "M115");
  CHECK_FALSE(h.finished(0.2, 0.1));
  CHECK(h.ok(0.2) == Handshake::Answer::Capabilities);
  // A late answer to a repeated question is one too many.
  CHECK(h.ok(0.21) == Handshake::Answer::Extra);
  // Printing starts once the link is quiet for a moment after the answer.
  CHECK_FALSE(h.finished(0.22, 0.21));
  CHECK(h.deadline(0.21) > 0.21);
  CHECK(h.finished(h.deadline(0.21), 0.21));
}

TEST_CASE("handshake: an unanswered question is asked again every min(1 s, timeout / 3)", "[serial][handshake]") {
  Handshake h(10);
  h.begin(0);
  CHECK(h.deadline(0) == 1);
  CHECK(h.due(0.99) == Handshake::Due::Wait);
  CHECK(h.due(1) == Handshake::Due::AskAgain);
  CHECK(h.deadline(1) == 2);
  CHECK(h.due(1.5) == Handshake::Due::Wait);
  // M110's ok restarts the retry timer for M115.
  CHECK(h.ok(1.7) == Handshake::Answer::AskCapabilities);
  CHECK(h.due(2.5) == Handshake::Due::Wait);
  CHECK(h.due(2.7) == Handshake::Due::AskAgain);
  // A short timeout asks three times within it.
  Handshake quick(0.6);
  quick.begin(0);
  CHECK(quick.deadline(0) == Approx(0.2));
}

TEST_CASE("handshake: at the timeout M110 unanswered is no printer, M115 unanswered prints without it",
          "[serial][handshake]") {
  Handshake silent(3);
  silent.begin(0);
  CHECK(silent.deadline(0) == 1);
  CHECK(silent.due(3) == Handshake::Due::NoAnswer);
  Handshake no_caps(3);
  no_caps.begin(0);
  no_caps.ok(0.1);
  CHECK(no_caps.due(2.9) == Handshake::Due::AskAgain);
  CHECK(no_caps.deadline(2.9) == 3);  // the timeout comes before the next retry
  CHECK(no_caps.due(3) == Handshake::Due::WithoutCapabilities);
}

TEST_CASE("handshake: a greeting asks M110 again, unless a resume keeps the running printer's numbering",
          "[serial][handshake][resume]") {
  Handshake boot(10);
  boot.begin(0);
  boot.ok(0.1);
  boot.ok(0.2);
  // A board that was still booting (it restarted after M110's ok, and forgot it).
  CHECK(boot.greeted());
  CHECK(boot.step() == Handshake::Step::Numbering);
  CHECK(boot.question() == "M110 N0");
  CHECK_FALSE(boot.finished(10, 0));
  // A resume onto a printer that kept running asks M115 only; a greeting
  // then is a reset, not the handshake's business.
  Handshake resume(10);
  resume.resume_running_printer();
  CHECK(resume.keeps_numbering());
  CHECK(resume.begin(0) == "M115");
  CHECK_FALSE(resume.greeted());
  // After that reset the numbering goes on from the print: M110 again.
  resume.number_on_from(40);
  CHECK_FALSE(resume.keeps_numbering());
  CHECK(resume.begin(1) == "M110 N40");
}

TEST_CASE("handshake: the sender prints without capabilities when M110 is answered and M115 is not",
          "[serial][handshake]") {
  SenderConfig sc;
  sc.timeout = 3;
  sc.finish_with_m400 = false;
  Sender s(sc, Sender::Logger());
  s.start(0);
  REQUIRE(s.output() == "M110 N0\n");
  s.written(s.output().size(), 0);
  s.on_line("ok", 0.1);
  REQUIRE(s.output() == "M115\n");
  s.written(s.output().size(), 0.1);
  CHECK(s.state() == SenderState::Capabilities);
  s.submit("G1 X10 F600", 1, 1);
  // M115 asked again until the timeout, then the first line.
  for (double t = 0.2; t < 3; t += 0.1) s.on_timer(t);
  CHECK(s.output() == "M115\nM115\n");
  s.written(s.output().size(), 2.9);
  s.on_timer(3);
  CHECK(s.state() == SenderState::Printing);
  CHECK(s.firmware().name.empty());
  CHECK(s.output().find("N1 G1 X10 F600*") == 0);
}
