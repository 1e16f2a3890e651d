#pragma once
// The Grosjean beam: this project's construction for the searchlight problem, not a published
// model. It follows Grosjean's split of a point source (models/point_source_grosjean.hpp;
// Grosjean 1956, as d'Eon & Irving 2011 use it) along the pencil beam, and keeps that split
// exact where a half-space allows it:
//
//  - The beam's first collisions at depth z' have density s exp(-s z') per unit power entering
//    (s = sigma_t'; reduced coefficients throughout, similarity relations, Bitterli eqs.
//    2.23-2.24) and re-emit alpha' of it isotropically.
//  - Once scattered: light of that emission that reaches the surface uncollided. A straight
//    path from (0, z') to the surface point at distance r has cosine mu = z' / d to the normal,
//    d = sqrt(r^2 + z'^2), and leaves with the exact dielectric transmittance T(mu) =
//    1 - F_r(mu, 1 / eta) (core/fresnel.hpp):
//      R_1(r) = int alpha' s e^{-s z'} z' e^{-s d} T(z'/d) / (4 pi d^3) dz'.
//    Over an annulus, r dr = d dd and z' dd / d^2 = -dmu turn the r integral into
//      int_r0^r1 2 pi r [...] dr = (1/2) int_{mu(r1)}^{mu(r0)} T(mu) e^{-s z' / mu} dmu,
//    and over the whole surface into the escape probability of the emission,
//      P(z') = (1/2) int_0^1 T(mu) e^{-s z' / mu} dmu          (= E_2(s z') / 2 at eta = 1).
//  - Multiply scattered: Grosjean's kernel alpha' exp(-sigma_tr rho) / (4 pi D rho) assumes that
//    all of an emission collides again, as in an infinite medium. In the half-space the part
//    P(z') that escaped does not, so the diffusion source at z' has strength
//      alpha' * alpha' (1 - P(z')),
//    bounded by the better dipole's image about the extrapolated boundary and read out as its
//    exitance, C_phi phi + C_E E (d'Eon 2012; models/dipole.hpp), with Grosjean's
//    D = (2 sigma_a + sigma_s') / (3 sigma_t'^2), sigma_tr = sqrt(sigma_a / D).
//    Without the factor (1 - P) the escaping light is counted twice, once as exitance and
//    again as a source (R_dr = 1.15 at alpha' = 1, eta = 1); with it, at alpha' = 1 the
//    diffusion part returns all of its source (the better dipole's total is C_E + 2 A C_phi = 1
//    at sigma_tr = 0), so R_dr = int s e^{-s z'} [P + (1 - P)] dz' = 1 exactly, and below 1
//    for any alpha' < 1.
//  - The unscattered beam exp(-s z) on the axis adds to the fluence only (it never leaves).
//
// At g = 0 the once-scattered part is exact (the straight path is the only one), which the
// tests hold against the refractive single-scatter solver; for g != 0 it is the once-scattered
// light of the similar isotropic medium.
//
// Units as models/dipole.hpp: lengths in the medium's unit, R_d and phi in 1 / length^2 per
// unit power entering the medium. Normal incidence only. As r -> 0 the once-scattered part goes
// as alpha' s int_0^1 T dmu / (4 pi r) (substitute z' = r u), so R_d(0) = +infinity; annulus
// averages, cell averages and totals are finite.
//
// Cost: P(z') is a 48-point Gauss-Legendre sum over mu (weights computed once per model); a
// point value or an annulus average is one adaptive quadrature (over z', or over mu for the
// once-scattered annulus), a fluence cell average a nested one.

#include <span>
#include <vector>

#include "scatterlab/core/exponential_sum.hpp"
#include "scatterlab/models/half_space_medium.hpp"

namespace scatterlab {

// Which scattering orders of the model (the unscattered beam is in the fluence of `all` only).
enum class ModelPart { single, multiple, all };

struct GrosjeanBeam {
  double sigma_t = 1.0;          // s = sigma_t', 1 / length
  double albedo = 0.0;           // alpha'
  double diffusion = 0.0;        // D, length
  double sigma_tr = 0.0;         // 1 / length
  double boundary_height = 0.0;  // z_b = 2 A D, length
  double fluence_weight = 0.25;  // C_phi
  double flux_weight = 0.5;      // C_E
  double eta = 1.0;              // n_medium / n_outside
  // P(z') = sum_k w_k exp(-sigma_t' z' / mu_k), Gauss-Legendre over the exit cosines mu_k:
  // escape(sigma_t' z').
  ExponentialSum escape;
};

GrosjeanBeam grosjean_beam(const HalfSpaceMedium& medium);

// P(z'): the fraction of an isotropic emission at depth z' >= 0 that leaves uncollided.
double grosjean_beam_escape(const GrosjeanBeam& model, double depth);

double grosjean_beam_reflectance(const GrosjeanBeam& model, double r, ModelPart part);
double grosjean_beam_total_reflectance(const GrosjeanBeam& model, ModelPart part);
std::vector<double> grosjean_beam_reflectance_annulus_average(const GrosjeanBeam& model,
                                                              std::span<const double> r_edges,
                                                              ModelPart part);
// phi(r, z) for r > 0, z >= 0, every order (the unscattered beam is a line on the axis).
double grosjean_beam_fluence(const GrosjeanBeam& model, double r, double z);
// Row-major [r][z], every order; the unscattered beam included in cells with r0 = 0.
std::vector<double> grosjean_beam_fluence_cell_average(const GrosjeanBeam& model,
                                                       std::span<const double> r_edges,
                                                       std::span<const double> z_edges);

}  // namespace scatterlab
