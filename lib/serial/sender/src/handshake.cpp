#include "gcode/serial/sender/handshake.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace gcode::serial {

std::string Handshake::begin(double now) {
  start_ = retry_ = now;
  answered_ = false;
  // Unnumbered: Marlin only checks numbers on lines that start with N, and
  // M110 N0 makes the next numbered line N1. A resume keeps the numbering;
  // the capabilities (and a simulated printer's time scale) are asked again.
  step_ = keeps_numbering() ? Step::Capabilities : Step::Numbering;
  return question();
}

std::string Handshake::question() const {
  return step_ == Step::Numbering ? fmt::format("M110 N{}", number_) : std::string("M115");
}

Handshake::Answer Handshake::ok(double now) {
  if (step_ == Step::Numbering) {
    step_ = Step::Capabilities;
    retry_ = now;
    return Answer::AskCapabilities;
  }
  const Answer a = answered_ ? Answer::Extra : Answer::Capabilities;
  answered_ = true;
  return a;
}

bool Handshake::greeted() {
  if (keeps_numbering()) return false;
  step_ = Step::Numbering;
  answered_ = false;
  return true;
}

double Handshake::retry_interval() const { return std::min(1.0, timeout_ / 3); }

Handshake::Due Handshake::due(double now) {
  if (now >= start_ + timeout_) return step_ == Step::Capabilities ? Due::WithoutCapabilities : Due::NoAnswer;
  if (now < retry_ + retry_interval()) return Due::Wait;
  retry_ = now;
  return Due::AskAgain;
}

double Handshake::deadline(double last_rx) const {
  if (answered_) return last_rx + kQuietStart;
  return std::min(retry_ + retry_interval(), start_ + timeout_);
}

}  // namespace gcode::serial
