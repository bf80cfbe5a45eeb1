#pragma once
// The questions before the first line: M110 N<n> until the firmware answers
// (its next numbered line is n + 1), then M115 for its capabilities
// (protocol.hpp's read_capability reads the answer). Each is asked again
// every min(1 s, timeout / 3) until `timeout` has passed since the first:
// then a firmware that answered M110 but not M115 is printed to without its
// capabilities, one that answered nothing is not there. Printing starts once
// the link has been quiet for a moment after M115's answer, so a late "ok"
// to a repeated M110 cannot be taken for the first line's.
//
// The sender (sender.hpp) sends what it returns and decides nothing of this.
#include <cstdint>
#include <string>

namespace gcode::serial {

class Handshake {
 public:
  enum class Step : std::uint8_t { Numbering, Capabilities };  // M110 asked, M115 asked
  enum class Answer : std::uint8_t {
    AskCapabilities,  // M110's ok: M115 goes out
    Capabilities,     // the first ok to M115 (Klipper's carries FIRMWARE_NAME)
    Extra,            // another: a late answer to a repeated M110 or M115
  };
  enum class Due : std::uint8_t {
    Wait,
    AskAgain,             // question() goes out again
    WithoutCapabilities,  // M110 answered, M115 not: print without them
    NoAnswer,             // nothing answered within the timeout
  };

  explicit Handshake(double timeout) : timeout_(timeout) {}

  // M110 N this: the line before the next one numbered (0 at first; after a
  // reset the last number that went out, so a number names one command).
  void number_on_from(long long n) { number_ = n; }
  long long number() const { return number_; }
  // A resume onto a printer that kept running (Sender::continue_from).
  void resume_running_printer() { resumed_ = true; }
  bool resumed() const { return resumed_; }
  // Such a resume, no reset since: M110 would throw away the numbering the
  // print goes on with, so only M115 is asked; and a greeting now is a
  // reset that lost the print, not a board still booting.
  bool keeps_numbering() const { return resumed_ && number_ == 0; }

  // The first question goes out `now`; returns it.
  std::string begin(double now);
  Step step() const { return step_; }
  // What the step asks: "M110 N<number>" or "M115".
  std::string question() const;
  // An "ok" during the handshake.
  Answer ok(double now);
  // The printer's greeting during the handshake: true when M110 goes out
  // again (question()), a board that was still booting (or after M110 was
  // answered: it restarted again, and forgot it); false when it keeps
  // numbering (the print it held is lost: a reset).
  bool greeted();
  // M115 answered and the link quiet since `last_rx` (the last byte of anything).
  bool finished(double now, double last_rx) const { return answered_ && now >= last_rx + kQuietStart; }
  Due due(double now);
  double deadline(double last_rx) const;

 private:
  static constexpr double kQuietStart = 0.05;  // quiet link after M115's answer before the first line
  double retry_interval() const;

  double timeout_;
  long long number_ = 0;
  bool resumed_ = false;
  Step step_ = Step::Numbering;
  double start_ = 0;
  double retry_ = 0;
  bool answered_ = false;  // M115 answered
};

}  // namespace gcode::serial
