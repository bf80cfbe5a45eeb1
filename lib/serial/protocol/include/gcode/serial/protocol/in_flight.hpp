#pragma once
// The sender's ledger of what is on its way to the printer and not answered
// yet, in the order it was written: the file's numbered lines and the
// sender's own (an M105 question, a pace probe), numbered too once printing
// has begun, so that line noise cannot turn them into another command. It
// owns the rule of answers: every line in flight gets one answer, in order,
// and each "ok" frees what it answers for (answer_to), no more.
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <deque>

#include "gcode/serial/protocol/protocol.hpp"

namespace gcode::serial {

class InFlight {
 public:
  static constexpr double kNotArrived = 1e300;

  // A line of the sender's own: what its answer tells.
  enum class Own : std::uint8_t {
    None,
    Question,   // an M105 the sender asks with (its answer proves every line before it ran)
    PaceProbe,  // a move of no length the pacer asks with (pacer.hpp)
  };

  // What a numbered line is, as the sender's timers ask it of everything in
  // flight on every turn: counted as entries come and go instead of walking
  // the queue each time (a fifth of the sender's time in its simulations).
  enum Mark : std::uint8_t {
    kLongRunning = 1,  // M109, G28, M400 ...: its answer may take long
    kUnbounded = 2,    // for a time nothing in the file tells
    kSilentWait = 4,   // waits for the user without a word (Prusa's M600)
    kMove = 8,         // takes a planner block
  };

  struct Entry {
    long long number;            // its line number (0: an unnumbered one)
    std::uint32_t bytes;
    bool temperature_query;      // M105: answered in order with "ok T:..."
    std::uint8_t marks;          // Mark bits
    std::uint64_t end;           // output offset just after its last byte
    double arrival;              // when it reached the printer (kNotArrived: not written yet)
    Own own;                     // a line of the sender's own
  };

  // What an "ok" answers for.
  struct Answer {
    enum class Kind : std::uint8_t {
      Stray,    // nothing in flight (counted, frees nothing)
      Through,  // every entry up to `index` is answered
      Question, // only the unnumbered question at `index` (ADVANCED_OK's ok without N)
    };
    Kind kind = Kind::Stray;
    std::size_t index = 0;
    // Our questions right behind the one answered, taken with it: their own
    // answers are still to come, and must not be taken for a later one's.
    std::size_t written_off = 0;
  };
  // `numbered_oks`: ADVANCED_OK, "ok N<n>" answers line n.
  Answer answer_to(const Response& ok, bool numbered_oks) const;

  void push(long long number, std::size_t bytes, bool temperature_query, std::uint64_t end,
            std::uint8_t marks = 0, Own own = Own::None) {
    entries_.push_back({number, static_cast<std::uint32_t>(bytes), temperature_query, marks, end, kNotArrived, own});
    bytes_ += bytes;
    count(entries_.back(), 1);
  }
  Entry pop_front();
  void erase(std::size_t index);
  // A resend of line n: every entry from n on (and any question behind
  // them) is lost or will be rejected. Returns their bytes.
  std::size_t drop_from(long long n);
  void clear() {
    entries_.clear();
    bytes_ = 0;
    counts_ = {};
    marked_ = {};
  }
  // Entries whose last byte is within the first `written` bytes ever
  // written reach the printer at the time `arrival(bytes written after them)` says.
  template <class Arrival>
  void written(std::uint64_t written, Arrival arrival) {
    for (Entry& e : entries_) {
      if (e.end > written) break;
      if (e.arrival == kNotArrived) e.arrival = arrival(static_cast<std::size_t>(written - e.end));
    }
  }

  bool empty() const { return entries_.empty(); }
  std::size_t size() const { return entries_.size(); }
  std::size_t bytes() const { return bytes_; }
  // Lines that hold a place in the printer's queue until answered: the
  // numbered ones and a pace probe (which waits for a planner block).
  std::size_t lines() const { return entries_.size() - counts_.questions; }
  // A question of the sender's (M105) is among them.
  bool asking() const { return counts_.questions > 0; }
  bool probing() const { return counts_.probes > 0; }
  // Entries in flight with `mark`.
  std::size_t marked(Mark mark) const { return marked_[static_cast<std::size_t>(std::countr_zero(static_cast<unsigned>(mark)))]; }
  const Entry& front() const { return entries_.front(); }
  const Entry& operator[](std::size_t i) const { return entries_[i]; }
  auto begin() const { return entries_.begin(); }
  auto end() const { return entries_.end(); }

 private:
  static constexpr std::size_t kMarks = 4;  // the bits of Mark
  struct Counts {
    std::size_t questions = 0, probes = 0;
  };
  // `e` comes (+1) or goes (-1).
  void count(const Entry& e, int sign);

  std::deque<Entry> entries_;
  std::size_t bytes_ = 0;
  Counts counts_;
  std::array<std::size_t, kMarks> marked_{};  // by Mark's bit
};

}  // namespace gcode::serial
