#pragma once
// An exact decimal: coordinates, E and F as the slicer wrote them.
//
// G-code numbers are short decimals ("5.0348", "-.8", "7800"). Held as
// binary doubles, sums drift (0.1 + 0.2) and inserted arithmetic comes out
// with binary noise (5.0348 - 2 = 3.0347999999999997). A Fixed holds a value
// as an integer count of 10^-9, so every number a slicer writes (up to nine
// decimals) is held exactly, sums of relative moves are exact, and E - 2 or
// Z + lift is the decimal the user means. Doubles are made only where
// geometry needs them (lengths, arcs, time), and to_double() gives exactly
// the double that parsing the decimal text would give.
//
// Range: +-9.2e9 mm, far beyond any printer; arithmetic saturates there
// instead of wrapping, so junk input (X1e300) cannot overflow.
#include <compare>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace gcode {

class Fixed {
 public:
  static constexpr int kDecimals = 9;
  static constexpr std::int64_t kOne = 1'000'000'000;
  static constexpr std::int64_t kMax = std::numeric_limits<std::int64_t>::max() / 2;
  // 10^0 .. 10^18, every power an int64_t holds.
  static constexpr std::int64_t kPowersOf10[] = {1,
                                                 10,
                                                 100,
                                                 1000,
                                                 10000,
                                                 100000,
                                                 1000000,
                                                 10000000,
                                                 100000000,
                                                 1000000000,
                                                 10000000000,
                                                 100000000000,
                                                 1000000000000,
                                                 10000000000000,
                                                 100000000000000,
                                                 1000000000000000,
                                                 10000000000000000,
                                                 100000000000000000,
                                                 1000000000000000000};

  constexpr Fixed() = default;
  static constexpr Fixed from_units(std::int64_t units) { return Fixed(clamp(units)); }
  // mantissa x 10^-decimals, as a word is written ("-.80": -80, 2). Exact
  // for up to nine decimals; more are rounded half away from zero.
  // Inline for what slicers write: a mantissa below 2^32 times 10^9 stays far
  // inside kMax, so it needs no saturation check (callgrind: the check and
  // the call were 5 % of a full pass's instructions).
  [[gnu::always_inline]] static Fixed from_decimal(std::int64_t mantissa, int decimals) {
    // The range test in unsigned arithmetic, where a mantissa near the
    // int64 limits wraps instead of overflowing.
    constexpr auto small = static_cast<std::uint64_t>(kSmall);
    if (static_cast<std::uint64_t>(mantissa) + small < 2 * small && decimals >= 0 && decimals <= kDecimals)
      return Fixed(mantissa * kPowersOf10[kDecimals - decimals]);
    return from_decimal_slow(mantissa, decimals);
  }
  // Rounded half away from zero to 10^-9; NaN is 0, infinities clamp.
  static Fixed from_double(double value);
  static constexpr Fixed from_int(std::int64_t whole) { return from_units(mul_sat(whole, kOne)); }

  constexpr std::int64_t units() const { return units_; }
  // Exactly the double nearest to the decimal: below 2^53 the integer is
  // exact, so one IEEE division rounds correctly, as parsing the text does.
  double to_double() const { return static_cast<double>(units_) / 1e9; }
  // The value rounded to `decimals` (0..9) digits, half away from zero, in
  // units of 10^-decimals: what format_scaled writes.
  std::int64_t scaled(int decimals) const;
  // Rounds to `decimals` digits (what is written with that many).
  Fixed rounded(int decimals) const;
  // Writes the value with at most `decimals` digits, trailing zeros dropped,
  // never an exponent ("3.0348", "-0.8", "5"). Returns the chars written
  // (at most kMaxNumberChars of number.hpp).
  std::size_t format(int decimals, char* out) const;

  constexpr bool is_zero() const { return units_ == 0; }
  constexpr Fixed operator-() const { return Fixed(-units_); }
  constexpr Fixed operator+(Fixed o) const { return Fixed(clamp(add_sat(units_, o.units_))); }
  constexpr Fixed operator-(Fixed o) const { return Fixed(clamp(add_sat(units_, -o.units_))); }
  Fixed& operator+=(Fixed o) { return *this = *this + o; }
  Fixed& operator-=(Fixed o) { return *this = *this - o; }
  friend constexpr bool operator==(Fixed a, Fixed b) { return a.units_ == b.units_; }
  friend constexpr auto operator<=>(Fixed a, Fixed b) { return a.units_ <=> b.units_; }

 private:
  static constexpr std::int64_t kSmall = std::int64_t{1} << 32;  // x 10^9 stays below kMax
  static Fixed from_decimal_slow(std::int64_t mantissa, int decimals);
  constexpr explicit Fixed(std::int64_t units) : units_(units) {}
  static constexpr std::int64_t clamp(std::int64_t u) { return u > kMax ? kMax : (u < -kMax ? -kMax : u); }
  static constexpr std::int64_t add_sat(std::int64_t a, std::int64_t b) {
    std::int64_t r = 0;
    if (__builtin_add_overflow(a, b, &r)) return a > 0 ? kMax : -kMax;
    return r;
  }
  static constexpr std::int64_t mul_sat(std::int64_t a, std::int64_t b) {
    std::int64_t r = 0;
    if (__builtin_mul_overflow(a, b, &r)) return (a > 0) == (b > 0) ? kMax : -kMax;
    return r;
  }

  std::int64_t units_ = 0;
};

}  // namespace gcode
