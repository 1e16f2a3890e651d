#pragma once
// Phase functions p(cos theta), with cos theta between the incoming and the outgoing travel
// directions, normalised so that the integral over the sphere is 1 (units 1/sr).

#include <algorithm>
#include <cmath>

#include "scatterlab/core/constants.hpp"

namespace scatterlab {

struct IsotropicPhase {
  double evaluate(double /*cos_theta*/) const { return inv_four_pi; }
  double sample_cos_theta(double xi) const { return 2.0 * xi - 1.0; }
  double mean_cosine() const { return 0.0; }
};

// Henyey-Greenstein (Vavassori §3, eq. of the HG phase function):
//   p(mu) = (1 - g^2) / (4 pi (1 + g^2 - 2 g mu)^{3/2}).
struct HenyeyGreenstein {
  double g;

  double evaluate(double cos_theta) const {
    // With a = |g| and m = sign(g) mu: 1 + g^2 - 2 g mu = (1 - a)^2 + 2 a (1 - m), a sum of
    // non-negative terms, so there is no cancellation as |g| -> 1 in the forward peak.
    const double a = std::abs(g);
    const double m = std::copysign(1.0, g) * cos_theta;
    const double base = (1.0 - a) * (1.0 - a) + 2.0 * a * (1.0 - m);
    return inv_four_pi * (1.0 - a) * (1.0 + a) / (base * std::sqrt(base));
  }

  // Inverts the HG cumulative distribution. The textbook form
  //   mu = (1 + g^2 - ((1 - g^2) / (1 - g + 2 g xi))^2) / (2 g)
  // divides by g and cancels as g -> 0. Subtracting the isotropic sample s = 2 x - 1 gives
  //   mu = s + 2 a x (1 - x) ((1 - a)(3 + a) + 4 a x) / ((1 - a) + 2 a x)^2
  // for a = |g| >= 0: every factor of the correction is non-negative, it vanishes linearly as
  // a -> 0 (so g = 1e-9 is exact to rounding), and it tends to 1 - s as a -> 1. Negative g
  // mirrors the lobe, p_g(mu) = p_{-g}(-mu), with x = 1 - xi so that mu still grows with xi.
  double sample_cos_theta(double xi) const {
    const double a = std::abs(g);
    const double x = std::signbit(g) ? 1.0 - xi : xi;
    const double s = 2.0 * x - 1.0;
    const double d = (1.0 - a) + 2.0 * a * x;
    const double correction =
        2.0 * a * x * (1.0 - x) * ((1.0 - a) * (3.0 + a) + 4.0 * a * x) / (d * d);
    return std::copysign(1.0, g) * std::clamp(s + correction, -1.0, 1.0);
  }

  double mean_cosine() const { return g; }
};

}  // namespace scatterlab
