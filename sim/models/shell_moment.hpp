#pragma once
// Shared by the infinite-medium diffusion approximations (private to sim/models): checks in the
// words of models/point_source_exact.hpp, and int_rho0^rho1 rho exp(-s rho) drho in closed form.

#include <cmath>
#include <string>

#include "scatterlab/core/error.hpp"

namespace scatterlab::detail {

inline void check_point_source_albedo(double albedo) {
  if (!(albedo >= 0.0 && albedo < 1.0)) {
    throw InputError("albedo", "got " + std::to_string(albedo), "a number in [0, 1)");
  }
}

inline void check_point_source_rho(double rho) {
  if (!(rho > 0.0) || !std::isfinite(rho)) {
    throw InputError("rho", "got " + std::to_string(rho), "a finite number > 0 (mfp)");
  }
}

inline void check_shell(double rho0, double rho1, bool allow_infinite) {
  if (!(rho0 >= 0.0) || !std::isfinite(rho0)) {
    throw InputError("rho0", "got " + std::to_string(rho0), "a finite number >= 0 (mfp)");
  }
  if (!(rho1 > rho0) || (!allow_infinite && !std::isfinite(rho1))) {
    throw InputError("rho1", "got " + std::to_string(rho1),
                     allow_infinite ? "a number > rho0 (mfp), or infinity"
                                    : "a finite number > rho0 (mfp)");
  }
}

// int_rho0^rho1 rho exp(-s rho) drho = [F(rho0) - F(rho1)] / s^2, F(x) = (1 + s x) exp(-s x);
// (rho1^2 - rho0^2) / 2 at s = 0. For s (rho1 - rho0) small that difference cancels, and the
// integral is taken by Simpson's rule instead (below).
inline double linear_exponential_moment(double s, double rho0, double rho1) {
  if (s == 0.0) return 0.5 * (rho1 - rho0) * (rho1 + rho0);
  if (std::isinf(rho1)) return (1.0 + s * rho0) * std::exp(-s * rho0) / (s * s);
  const double x0 = s * rho0, x1 = s * rho1;
  if (x1 - x0 > 1e-3) {
    return ((1.0 + x0) * std::exp(-x0) - (1.0 + x1) * std::exp(-x1)) / (s * s);
  }
  // Thin shell: F'(x) = -x exp(-x), so the difference is int_x0^x1 x exp(-x) dx; Simpson's rule
  // on a width h below 1e-3 is exact to ~h^4 / 2880 < 1e-15 relative.
  const double xm = 0.5 * (x0 + x1);
  const double h = x1 - x0;
  const double integral =
      h / 6.0 * (x0 * std::exp(-x0) + 4.0 * xm * std::exp(-xm) + x1 * std::exp(-x1));
  return integral / (s * s);
}

}  // namespace scatterlab::detail
