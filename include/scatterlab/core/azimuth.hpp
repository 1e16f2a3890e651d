#pragma once
// (cos 2 pi u, sin 2 pi u) for u in [0, 1): the azimuth of every scattering event.
//
// The library sin and cos cost more than the rest of an event's direction update together, and
// their general argument reduction is wasted here: u is already the angle in turns, so the
// quadrant is the integer part of 4u and the remainder maps exactly to [-pi/4, pi/4], where
// Taylor series to x^15 and x^16 are accurate to a few 1e-17 ((pi/4)^17 / 17! = 4.4e-17).

#include <cmath>
#include <numbers>

namespace scatterlab {

struct UnitCircle {
  double cos;
  double sin;
};

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
  // Horner forms of the Taylor series of sin x / x and cos x about 0.
  double s = 1.0 / 1307674368000.0;  // 1/15!
  s = s * -x2 + 1.0 / 6227020800.0;  // 1/13!
  s = s * -x2 + 1.0 / 39916800.0;
  s = s * -x2 + 1.0 / 362880.0;
  s = s * -x2 + 1.0 / 5040.0;
  s = s * -x2 + 1.0 / 120.0;
  s = s * -x2 + 1.0 / 6.0;
  s = (s * -x2 + 1.0) * x;
  double c = 1.0 / 20922789888000.0;  // 1/16!
  c = c * -x2 + 1.0 / 87178291200.0;  // 1/14!
  c = c * -x2 + 1.0 / 479001600.0;
  c = c * -x2 + 1.0 / 3628800.0;
  c = c * -x2 + 1.0 / 40320.0;
  c = c * -x2 + 1.0 / 720.0;
  c = c * -x2 + 1.0 / 24.0;
  c = c * -x2 + 0.5;
  c = c * -x2 + 1.0;
  // Rotate by q quarter turns: (c, s) -> (-s, c) per turn. Odd turns swap the pair; the signs
  // come from a table (times +-1 is exact), so that no branch depends on the random number.
  constexpr double cos_sign[4] = {1.0, -1.0, -1.0, 1.0};
  constexpr double sin_sign[4] = {1.0, 1.0, -1.0, -1.0};
  const int turn = static_cast<int>(q) & 3;
  const double pair[2] = {c, s};
  return {pair[turn & 1] * cos_sign[turn], pair[(turn & 1) ^ 1] * sin_sign[turn]};
}

}  // namespace scatterlab
