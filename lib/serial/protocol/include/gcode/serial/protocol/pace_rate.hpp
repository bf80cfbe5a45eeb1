#pragma once
// How fast the printer really runs its moves against the file's feed rates:
// a speed factor (2: a move of 1 s at its feed rate takes 0.5 s), learnt
// online for the pacer (pacer.hpp).
//
// Two kinds of evidence, of different worth:
//  * a floor (at_least): a speed the printer has shown, from counts and the
//    host's own clock (a block must have ended for the next move to be
//    answered, and no move starts before it was sent), which host latency
//    can only lower. The factor rises to it at once.
//  * samples between two moments the pacer saw blocks end (a sighting: the
//    answer to a move that waited for a block, or ADVANCED_OK's count of
//    free blocks): the factor with which the moves in between, each
//    starting when it was answered or when the one before ended, end
//    exactly at the second sighting. Each moves the estimate in proportion
//    to the moves it spans (a geometric mean, so that 0.5 and 2 weigh
//    alike). They follow a printer that slows down; the pacer keeps the
//    factor at its floor whatever they say.
namespace gcode::serial {

class PaceRate {
 public:
  static constexpr double kMin = 1;       // no slower than its file: the model never holds a move for a slow printer
  static constexpr double kMax = 64;      // faster than any link can feed it: no pacing
  static constexpr double kSpan = 32;     // moves of samples that replace the estimate
  static constexpr long long kMinSpan = 8; // moves a sample spans at least (latency is in each end)

  double factor() const { return factor_; }
  // A measured factor over `moves` moves.
  void sample(double factor, double moves);
  // The printer has shown it runs at least this fast.
  void at_least(double factor);

 private:
  double factor_ = 1;
};

}  // namespace gcode::serial
