#pragma once
// The ridge of once-scattered light that a pencil beam draws on the sphere of directions of
// every spatial bin: the second term of the adexp_ridge lobe model (lobe_model.hpp).
//
// The beam (unit power, along +z from the origin, lengths in mfp, Vavassori §4.1) scatters at
// (0, 0, z') into direction omega with power per unit length and solid angle
// sigma_s e^{-z'} p(cos theta), p the Henyey-Greenstein phase function (Vavassori §3.1). Seen
// from a point at distance r from the axis and height z, the point z' lies in the half-plane
// phi = 0 of its local frame (e_r, e_phi, e_z), at the angle theta of travel with
// z - z' = r cot theta and distance d = r / sin theta, so dz' = r d theta / sin^2 theta and
//   dE = sigma_s e^{-z'} p e^{-d} dz' / d^2 = sigma_s p e^{-(z' + d)} d theta / r,
//   z' + d = z + r (1 - cos theta) / sin theta = z + r tan(theta / 2).
// The radiance is a line on the sphere, phi = 0 exactly; its density across the line,
//   R(theta) = integral of L sin theta d phi = sigma_s p(cos theta) e^{-z - r tan(theta/2)} / r,
// for theta above the onset atan2(r, z) (z' >= 0) and 0 below.
//
// The fitted form keeps the shape and frees the constants, so that it needs neither g, nor the
// albedo, nor the bin's position:
//   R(theta) = A (1 - g^2) / (1 + g^2 - 2 g cos theta)^{3/2} e^{-k tan(theta/2)}
//              / (1 + e^{-(theta - theta_on) / w}),
// (the HG phase function times 4 pi, the attenuation, and a logistic onset: the spatial bin
// spreads atan2(r, z) over its extent in r and z). Parameters (A, g, k, theta_on, w).
//
// Light scattered twice or more after leaving the beam at a small angle stays near the line:
// the spread ridge, A_spread R(theta) / A e^{kappa (cos phi - 1)} (a von Mises profile in phi
// about the line, one-sided as the line is: phi = pi is the plane's other half), a radiance
// rather than a line density, with the line's profile in theta. Parameters (A_spread, kappa).
//
// A tally bin on the line (one whose phi range ends at phi = 0 or 2 pi) holds half of the
// ridge's power over its theta range, the bin across the line the other half:
//   <L>_bin = (1 / (2 Omega_bin)) integral over the bin's theta range of R(theta) d theta.
// On a folded grid the one bin at phi = 0 averages the line with its mirror image over twice
// its solid angle: the same formula. LobeGrid::ridge_nodes holds the quadrature of it.

#include <cmath>

namespace scatterlab::fit {

// log of R(theta) / A for ridge parameters (g, k, theta_on, w) = ridge[1..4].
template <typename T>
T log_ridge_profile(const T* ridge, double theta) {
  using std::exp;
  using std::log;
  using std::log1p;
  const T& g = ridge[1];
  const T& k = ridge[2];
  const T& onset = ridge[3];
  const T& width = ridge[4];
  const double cos_theta = std::cos(theta), tan_half = std::tan(0.5 * theta);
  const T phase = log(T(1) - g * g) - T(1.5) * log(T(1) + g * g - T(2) * g * cos_theta);
  // -log(1 + e^{-x}) without overflow for either sign of x.
  const T x = (T(theta) - onset) / width;
  const T onset_term = x > T(0) ? -log1p(exp(-x)) : x - log1p(exp(x));
  return phase - k * tan_half + onset_term;
}

}  // namespace scatterlab::fit
