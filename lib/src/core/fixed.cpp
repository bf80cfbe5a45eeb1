#include "gcode/core/fixed.hpp"

#include "gcode/core/number.hpp"

namespace gcode {

namespace {

// a / b rounded half away from zero (b > 0).
std::int64_t divide_rounded(std::int64_t a, std::int64_t b) {
  std::int64_t q = a / b;
  std::int64_t r = a % b;
  if (r < 0) r = -r;
  if (2 * r >= b) q += a < 0 ? -1 : 1;
  return q;
}

}  // namespace

Fixed Fixed::from_decimal_slow(std::int64_t mantissa, int decimals) {
  if (decimals >= 0 && decimals <= kDecimals) return from_units(mul_sat(mantissa, kPowersOf10[kDecimals - decimals]));
  if (decimals < 0) {
    // mantissa x 10^-decimals: whole tens first, saturating like the rest.
    std::int64_t whole = mantissa;
    for (int i = 0; i < -decimals && whole != 0 && whole < kMax && whole > -kMax; ++i) whole = mul_sat(whole, 10);
    return from_units(mul_sat(whole, kOne));
  }
  if (decimals - kDecimals > 18) return Fixed();
  return from_units(divide_rounded(mantissa, kPowersOf10[decimals - kDecimals]));
}

Fixed Fixed::from_double(double value) {
  if (!(value == value)) return Fixed();
  if (value >= static_cast<double>(kMax) / kOne) return Fixed(kMax);
  if (value <= -static_cast<double>(kMax) / kOne) return Fixed(-kMax);
  return Fixed(to_scaled(value, kDecimals));
}

std::int64_t Fixed::scaled(int decimals) const {
  if (decimals >= kDecimals) return units_;
  if (decimals < 0) decimals = 0;
  return divide_rounded(units_, kPowersOf10[kDecimals - decimals]);
}

Fixed Fixed::rounded(int decimals) const {
  if (decimals >= kDecimals) return *this;
  if (decimals < 0) decimals = 0;
  return Fixed(mul_sat(scaled(decimals), kPowersOf10[kDecimals - decimals]));
}

std::size_t Fixed::format(int decimals, char* out) const {
  if (decimals > kDecimals) decimals = kDecimals;
  if (decimals < 0) decimals = 0;
  return format_scaled(scaled(decimals), decimals, out);
}

}  // namespace gcode
