#pragma once
// How fast the printer really runs its moves against the file's feed rates:
// a speed factor (2: a move of 1 s at its feed rate takes 0.5 s), learnt
// online for the pacer (pacer.hpp).
//
// The pacer measures it between two moments it saw blocks end (a sighting:
// the answer to a move that waited for a block, or ADVANCED_OK's count of
// free blocks): the factor with which the moves in between, each starting
// when it was answered or when the one before ended, end exactly at the
// second sighting. Each such sample moves the estimate in proportion to the
// moves it spans (a geometric mean, so that 0.5 and 2 weigh alike), which
// smooths the host's own latency in each sighting. A planner found with
// room where the factor said it was full (a probe) says the printer is
// faster than that: the factor grows by a step at once.
namespace gcode::serial {

class PaceRate {
 public:
  static constexpr double kMin = 1;       // no slower than its file: the model never holds a move for a slow printer
  static constexpr double kMax = 64;      // faster than any link can feed it: no pacing
  static constexpr double kStep = 1.25;   // growth on a probe that found room
  static constexpr double kSpan = 32;     // moves of samples that replace the estimate
  static constexpr long long kMinSpan = 8; // moves a sample spans at least (latency is in each end)

  double factor() const { return factor_; }
  // A measured factor over `moves` moves.
  void sample(double factor, double moves);
  // The planner had room where the factor said it had none.
  void faster();

 private:
  double factor_ = 1;
};

}  // namespace gcode::serial
