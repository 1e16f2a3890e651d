#pragma once
// A diffusion BSSRDF on the lit sphere (Bitterli §3.5): the radiant exitance it gives on a sphere
// of radius R under a directional light along +z, integrated over the lit surface by Monte Carlo,
// so that it converges to the exact double integral (Bitterli eq. 2.14) and can be held against
// the path-traced lit sphere (transport/lit_object.hpp) in the same geometry, light and units.
//
// With the light's irradiance E_0 normal to its direction, the power entering at x_i per unit
// area is E_0 cos(theta_i) F_t(eta, theta_i); integrating eq. 2.14 with eq. 2.16 (bssrdf.hpp) over
// the directions that leave x_o, weighted by their cosine, gives
//   M(x_o) = exit_transmittance_ratio(eta) * int_lit E_0 cos(theta_i) F_t(eta, theta_i)
//            R_d(|x_o - x_i|) dA_i,
// the distance being the chord through the medium (Jensen et al. 2001's choice, as in every
// BSSRDF evaluation on a surface). Per unit power meeting the sphere, E_0 pi R^2 = 1, as the
// path-traced tallies are.
//
// Sampling: two strategies, combined by the balance heuristic (Veach 1997, §9.2.2: one sample of
// each, each weighted by f / (p_profile + p_light)), so that neither the profile's peak near x_o
// nor the lit side seen from the shadow side is left to chance.
//  - along the profile: on a sphere the area at chord distance d from x_o is d dd dbeta (beta
//    the azimuth about x_o): with gamma the central angle, d = 2 R sin(gamma / 2) and
//    dA = R^2 sin(gamma) dgamma dbeta = d dd dbeta, the same measure as a disc in the plane. So
//    d is drawn along 2 pi d R_d(d) on [0, 2R] (RadialProfileSampler) and beta uniformly:
//    p_profile = p(d) / (2 pi d) per unit area;
//  - along the light: uniformly over the sphere's shadow disc, projected onto the lit side:
//    p_light = cos(theta_i) / (pi R^2) per unit area.
// x_o is drawn uniformly over the area of each psi bin, so each bin's value is the bin's area
// average, as the tally's is.
//
// Each bin's standard error is the sample standard deviation over sqrt(samples), from one
// Philox stream per bin keyed by (seed, bin); for a measured profile (diffusion_profile.hpp) the
// rings' own standard errors are carried through the integral, which is linear in them.

#include <cstdint>
#include <span>
#include <vector>

#include "scatterlab/models/diffusion_profile.hpp"

namespace scatterlab {

struct LitSphereExitance {
  std::vector<double> mean;  // per psi bin, 1 / length^2 per unit power meeting the sphere
  std::vector<double> stderr_of_mean;  // same units
};

// psi_edges: the angle from the lit pole, in [0, pi], increasing (InputError "psi" otherwise);
// radius > 0 in the profile's length unit ("radius"); samples >= 2 per bin ("samples").
LitSphereExitance lit_sphere_exitance(const DiffusionProfile& profile, double radius,
                                      std::span<const double> psi_edges, int samples,
                                      std::uint64_t seed);

// The same M(psi_o) averaged over the bin [psi_lo, psi_hi], by a deterministic nested quadrature
// of Bitterli eq. 2.14 with eq. 2.16 over the lit hemisphere in spherical coordinates about the
// sphere's centre: Gauss-Legendre of `nodes` points in cos psi_o across the bin, adaptive
// Gauss-Kronrod in psi_i (split at psi_o and pi / 2) and in the azimuth (to relative 1e-8). It
// shares nothing with the sampling above but the profile and the Fresnel term.
double lit_sphere_exitance_quadrature(const DiffusionProfile& profile, double radius, double psi_lo,
                                      double psi_hi, int nodes = 8);

}  // namespace scatterlab
