#pragma once
// Chandrasekhar's H-function for isotropic scattering with single-scattering albedo w in [0, 1],
// the solution of the nonlinear integral equation (Chandrasekhar 1960, "Radiative Transfer",
// §26, eq. (41) with characteristic function w / 2)
//
//   H(mu) = 1 + (w / 2) mu H(mu) int_0^1 H(mu') / (mu + mu') dmu',   mu in [0, 1],
//
// and what it gives exactly for an index-matched half-space.
//
// Method: the closed integral form (Chandrasekhar 1960, §39, eq. (36); Fowler 1983; Kawabata &
// Limaye 2011, eq. (6))
//
//   ln H(mu) = -(mu / pi) int_0^{pi/2} ln(1 - w theta cot theta) / (cos^2 theta + mu^2 sin^2 theta)
//   dtheta,
//
// integrated by adaptive Gauss-Kronrod to 1e-13 relative. The integrand has only a logarithmic
// singularity at theta = 0 when w = 1, where 1 - theta cot theta ~ theta^2 / 3 is taken from
// its series so that the logarithm never sees a cancelled difference. Tests check it against
// the integral equation solved by iteration and against the moment identities.

namespace scatterlab {

// H(mu) for mu in [0, 1] and albedo w in [0, 1]; H(0) = 1 and H = 1 for w = 0. Throws
// InputError ("albedo", "mu") outside those ranges.
double chandrasekhar_h(double albedo, double mu);

// Total diffuse reflectance (plane albedo) of a semi-infinite, index-matched, isotropically
// scattering medium lit by a collimated beam at mu0 = cos(incidence) (Chandrasekhar 1960, §47,
// eq. (40)-(41); van de Hulst 1980, "Multiple Light Scattering", §14.4):
//   R(mu0) = 1 - H(mu0) sqrt(1 - w).
// A pencil beam integrated over the surface is the plane-parallel beam, so this is also the
// searchlight's total diffuse reflectance; for normal incidence mu0 = 1.
double half_space_diffuse_reflectance(double albedo, double mu0 = 1.0);

}  // namespace scatterlab
