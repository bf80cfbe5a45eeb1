// The sender's resend state machine (serial/resend.hpp) and question
// back-off (serial/probe_backoff.hpp).
#include <catch2/catch.hpp>

#include "gcode/serial/protocol/probe_backoff.hpp"
#include "gcode/serial/protocol/resend.hpp"

using namespace gcode::serial;
using Verdict = ResendState::Verdict;

TEST_CASE("resend: repeats for the line being resent are ignored while settling", "[serial][resend]") {
  ResendState r;
  CHECK(r.request(7, 10) == Verdict::Rewind);
  r.rewound(7, 1.0, 0.01);
  CHECK(r.settling());
  CHECK(r.request(7, 10) == Verdict::Repeat);  // a stale line behind the bad one
  CHECK(r.request(8, 10) == Verdict::Rewind);  // another line: a new request
  CHECK(r.count() == 1);
}

TEST_CASE("resend: the quiet counts from the last byte either way", "[serial][resend]") {
  ResendState r;
  r.rewound(3, 1.0, 0.5);
  CHECK_FALSE(r.quiet(1.4, 0));
  CHECK(r.quiet(1.5, 0));
  r.heard(2.0);
  CHECK_FALSE(r.quiet(2.4, 0));
  CHECK(r.quiet_at(2.2) == Approx(2.7));
  CHECK_FALSE(r.quiet(2.6, 2.2));
  CHECK(r.quiet(2.8, 2.2));
  r.settled();
  CHECK_FALSE(r.settling());
  r.heard(9);  // not settling: nothing to restart
  CHECK(r.quiet_at(0) == Approx(2.5));
}

TEST_CASE("resend: the same line asked for too often gives up", "[serial][resend]") {
  ResendState r;
  for (int i = 0; i < 3; ++i) {
    CHECK(r.request(5, 3) == Verdict::Rewind);
    r.rewound(5, i, 0);
    r.settled();
  }
  CHECK(r.request(5, 3) == Verdict::TooMany);
  CHECK(r.count() == 4);
}

TEST_CASE("resend: the ok right after a Resend is the rejected line's", "[serial][resend]") {
  ResendState r;
  r.expect_rejected_ok();
  CHECK(r.take_rejected_ok());
  CHECK_FALSE(r.take_rejected_ok());
  r.expect_rejected_ok();
  r.other_answer();  // an echo in between: that ok was lost
  CHECK_FALSE(r.take_rejected_ok());
}

TEST_CASE("probe back-off: three quick questions, each waiting twice as long", "[serial][resend]") {
  ProbeBackoff p;
  CHECK(p.quick());
  CHECK(p.when(10, 1) == 10);
  p.asked(10, 1);
  CHECK(p.when(10, 1) == 12);  // due + margin, and not before now + 2 margins
  CHECK(p.when(20, 1) == 21);
  p.asked(12, 1);
  CHECK(p.when(10, 1) == 16);
  p.asked(16, 1);
  CHECK_FALSE(p.quick());
  p.answered();
  CHECK(p.quick());
  CHECK(p.when(10, 1) == 10);
}
