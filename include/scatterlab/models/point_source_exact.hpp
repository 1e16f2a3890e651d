#pragma once
// Exact steady-state fluence of an isotropic point source of unit power in an infinite,
// homogeneous medium that scatters isotropically, with single-scattering albedo c in [0, 1).
// Lengths are in mean free paths (sigma_t = 1); fluence is in W mfp^-2 per W of source power
// (photons per unit area per unit time per photon emitted per unit time). The Monte Carlo
// transport is validated against these functions.
//
// Method (derived in point_source_exact.cpp, following Case, de Hoffmann & Placzek 1953,
// "Introduction to the Theory of Neutron Diffusion", vol. I, §4-§6; Case & Zweifel 1967,
// "Linear Transport Theory", §2.5 and §6; d'Eon, "A Hitchhiker's Guide to Multiple Scattering",
// the infinite-medium isotropic point source): the Fourier transform of the fluence,
// A(k) / (1 - c A(k)) with A(k) = arctan(k) / k, is inverted by closing the contour in the upper
// half plane. That leaves one discrete diffusion mode, exp(-rho / nu0), and a non-oscillatory
// integral over the branch cut nu in (0, 1) of exp(-rho / nu) times a smooth weight, which is
// integrated by adaptive Gauss-Kronrod quadrature (asked for 1e-13 relative; the tests find the
// point values within 1e-14 of 30-digit references for c in [0.01, 0.9999], rho in [0.05, 10]).
//
// Cost: one evaluation (point or shell) is one adaptive quadrature of a few hundred cheap
// integrand calls, ~20 microseconds in a release build; 200 shells take a few milliseconds.
//
// Input checks: albedo outside [0, 1) (or NaN) and rho that is not a finite number > 0 throw
// InputError naming the field ("albedo", "rho", "rho0", "rho1") and the accepted range.

namespace scatterlab {

// nu0 > 1, the root of 1 = c nu0 artanh(1 / nu0); the discrete mode decays as exp(-rho / nu0).
// nu0 -> 1 as c -> 0 (nu0 - 1 ~ 2 exp(-2 / c), which rounds to 0 for c below ~0.05, so this
// returns 1 there and for c = 0), and nu0 ~ 1 / sqrt(3 (1 - c)) as c -> 1.
double discrete_eigenvalue(double albedo);

// exp(-rho) / (4 pi rho^2): photons that have not collided yet.
double point_source_fluence_uncollided(double rho);

// Fluence of photons that have collided at least once; exactly 0 for c = 0.
double point_source_fluence_collided(double albedo, double rho);

// Total fluence: uncollided + collided.
double point_source_fluence(double albedo, double rho);

// Integral of the fluence over the volume of the spherical shell rho0 <= rho < rho1,
// 4 pi int rho^2 phi drho, in W mfp per W of source power (rho0 may be 0, rho1 may be
// +infinity). With sigma_t = 1 this is the expected number of collisions per source photon
// in the shell; (1 - c) times it is the fraction of the power absorbed there. Needs
// 0 <= rho0 < rho1.
double point_source_fluence_shell_integral(double albedo, double rho0, double rho1,
                                           bool include_uncollided = true);

// Volume average of the fluence over the shell rho0 <= rho < rho1 (rho0 may be 0, rho1 finite):
// the shell integral above divided by 4/3 pi (rho1^3 - rho0^3). This is what a Monte Carlo
// collision or track-length tally on radial shells estimates.
double point_source_fluence_shell_average(double albedo, double rho0, double rho1,
                                          bool include_uncollided = true);

}  // namespace scatterlab
