#pragma once
// The scaled complementary error function erfcx(x) = exp(x^2) erfc(x), which the standard
// library does not have, and 1 - sqrt(pi) x erfcx(x), the difference the quantized-diffusion
// flux terms need (private to sim/models; tests/unit/test_quantized_diffusion.cpp checks both
// against std::erfc where exp(x^2) and erfc(x) are both representable).

#include <cmath>
#include <numbers>

namespace scatterlab::detail {

// Below this argument exp(x^2) erfc(x) is computed as written: erfc(25) = 8.3e-274 is still a
// normal double (it leaves the normal range near x = 26.5), and the rounding of x * x is
// amplified by exp to at most x^2 eps = 625 * 1.1e-16 = 7e-14 relative.
inline constexpr double erfcx_series_from = 25.0;

// erfcx(x) = exp(x^2) erfc(x).
//  - x < 25: exp(x * x) * erfc(x). For x < 0 erfc(x) lies in (1, 2], so there is no
//    cancellation; the product overflows to +infinity below x = -26.6, where the true value
//    (about 2 exp(x^2)) is itself beyond the doubles. Callers that can meet negative arguments
//    (the fluence K below, quantized_diffusion.cpp) use erfc with a bounded exponent there.
//  - x >= 25: the asymptotic series (Abramowitz & Stegun 7.1.23)
//    1 / (x sqrt(pi)) (1 - 1/(2x^2) + 3/(4x^4) - 15/(8x^6) + 105/(16x^8)); the first omitted
//    term, 945 / (32 x^10) = 3.1e-13 at x = 25, bounds the truncation error (alternating series).
inline double erfcx(double x) {
  if (x < erfcx_series_from) return std::exp(x * x) * std::erfc(x);
  const double y = 1.0 / (x * x);
  return (1.0 + y * (-0.5 + y * (0.75 + y * (-1.875 + y * 6.5625)))) * std::numbers::inv_sqrtpi / x;
}

// 1 - sqrt(pi) x erfcx(x) for x >= 0: in (0, 1], ~ 1 / (2 x^2) for large x. Below 25 by the
// subtraction (it loses log10(2 x^2) <= 3.1 digits: relative error <= 1e-13); from 25 on the
// same series with its leading 1 cancelled analytically:
// 1/(2x^2) - 3/(4x^4) + 15/(8x^6) - 105/(16x^8), relative truncation error <= 4e-10 at x = 25.
inline double erfcx_complement(double x) {
  if (x < erfcx_series_from) return 1.0 - x * erfcx(x) / std::numbers::inv_sqrtpi;
  const double y = 1.0 / (x * x);
  return y * (0.5 + y * (-0.75 + y * (1.875 + y * -6.5625)));
}

}  // namespace scatterlab::detail
