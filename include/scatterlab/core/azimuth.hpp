#pragma once
// (cos 2 pi u, sin 2 pi u) for u in [0, 1): the azimuth of every scattering event.
//
// The library sin and cos cost more than the rest of an event's direction update together, and
// their general argument reduction is wasted here: u is already the angle in turns, so the
// quadrant is the integer part of 4u and the remainder maps exactly to [-pi/4, pi/4], where
// Taylor series to x^15 and x^16 are accurate to a few 1e-17 ((pi/4)^17 / 17! = 4.4e-17).

#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>

namespace scatterlab {

struct UnitCircle {
  double cos;
  double sin;
};

// 1 / n!, with n! exact in a double for n <= 18 (below 2^53), so the quotient is the literal's.
constexpr double inverse_factorial(int n) {
  double factorial = 1.0;
  for (int k = 2; k <= n; ++k) factorial *= k;
  return 1.0 / factorial;
}

// Horner coefficients, highest power first, of the Taylor series of sin x / x and cos x about 0
// in powers of -x^2 (also the lane walk's, transport/lane_walk.hpp).
inline constexpr std::array<double, 8> azimuth_sin_series{
    inverse_factorial(15), inverse_factorial(13), inverse_factorial(11), inverse_factorial(9),
    inverse_factorial(7),  inverse_factorial(5),  inverse_factorial(3),  1.0};
inline constexpr std::array<double, 9> azimuth_cos_series{
    inverse_factorial(16), inverse_factorial(14), inverse_factorial(12),
    inverse_factorial(10), inverse_factorial(8),  inverse_factorial(6),
    inverse_factorial(4),  inverse_factorial(2),  1.0};

inline UnitCircle azimuth(double u) {
  // Nearest quarter turn q and the signed remainder in radians.
  // Rounding by adding and subtracting 1.5 * 2^52 (exact for |4u| < 2^51: the sum's unit in the
  // last place is 1) is std::nearbyint in the default rounding mode, without the library call
  // that the x86-64 baseline (no SSE4.1 roundsd) makes of it.
  constexpr double round_shift = 0x1.8p52;
  const double quarters = 4.0 * u;
  const double q = (quarters + round_shift) - round_shift;
  const double x = (quarters - q) * (0.5 * std::numbers::pi);
  const double x2 = x * x;
  double s = azimuth_sin_series[0];
  for (std::size_t i = 1; i < azimuth_sin_series.size(); ++i) s = s * -x2 + azimuth_sin_series[i];
  s *= x;
  double c = azimuth_cos_series[0];
  for (std::size_t i = 1; i < azimuth_cos_series.size(); ++i) c = c * -x2 + azimuth_cos_series[i];
  // Rotate by q quarter turns: (c, s) -> (-s, c) per turn. Odd turns swap the pair; the signs
  // come from a table (times +-1 is exact), so that no branch depends on the random number.
  constexpr double cos_sign[4] = {1.0, -1.0, -1.0, 1.0};
  constexpr double sin_sign[4] = {1.0, 1.0, -1.0, -1.0};
  const int turn = static_cast<int>(q) & 3;
  const double pair[2] = {c, s};
  return {pair[turn & 1] * cos_sign[turn], pair[(turn & 1) ^ 1] * sin_sign[turn]};
}

}  // namespace scatterlab
