#pragma once
// The diffusion models' boundary condition at a refractive surface, as polynomial fits in the
// relative index eta = n_medium / n_outside (eta > 1: the medium is the denser one, so light
// inside meets total internal reflection). All are averages of the dielectric Fresnel
// reflectance F_r(eta, mu) seen from inside the medium, mu the cosine to the normal:
//   F_dr = 2 int_0^1 F_r mu dmu        (hemispherical diffuse reflectance, Bitterli eq. 2.29)
//   C_i  = int_0^1 F_r mu^i dmu        (Fresnel moments, d'Eon & Irving 2011, "A quantized-
//                                        diffusion model...", boundary conditions)
// so F_dr = 2 C_1. The exact dielectric Fresnel term is core/fresnel.hpp's business; these fits
// are what the published models were defined with, and the models use them as published.
//
// Equation numbers of d'Eon & Irving 2011 and d'Eon 2012 are not cited: those papers were not at
// hand; the polynomial coefficients are the published ones (as also used by pbrt-v3's
// FresnelMoment1/2), and tests/unit/test_boundary_reflection.cpp checks them against a direct
// quadrature of the Fresnel formula.
//
// Accepted eta: in [0.5, 2.5], where the fits stay within 0.006 of the quadrature (beyond, they
// leave it fast: 2 C_1(3) = 1.16 > 1); anything else is an InputError for "eta". At eta = 1 the
// fits give 2 C_1 = 0.0043 and 3 C_2 = -0.0066 instead of 0.

namespace scatterlab {

// F_dr of Egan & Hilgeman 1979 for eta >= 1 (Jensen et al. 2001 eq. 2.30 of Bitterli:
// F_dr = -1.440 / eta^2 + 0.710 / eta + 0.668 + 0.0636 eta), and 2 C_1(eta) of d'Eon & Irving
// for eta < 1, where the Egan-Hilgeman fit does not apply (it was made for eta > 1).
// Note F_dr(1) = 0.0016 from the Egan-Hilgeman fit, not exactly 0.
double diffuse_fresnel_reflectance(double eta);

// C_1 and C_2 of d'Eon & Irving 2011 (fits of degree 5 on each side of eta = 1).
double fresnel_moment1(double eta);
double fresnel_moment2(double eta);

// A of the classical dipole, (1 + F_dr) / (1 - F_dr) (Jensen et al. 2001 §2.3; Bitterli
// Listing A.2), and of the better dipole, (1 + 3 C_2) / (1 - 2 C_1) (d'Eon 2012, "A better
// dipole"; d'Eon & Irving 2011, boundary conditions). The extrapolated boundary sits z_b = 2 A D
// outside the surface (Bitterli §2.5).
double classical_boundary_a(double eta);
double better_boundary_a(double eta);

// Weights of fluence and normal flux in the exitance through the surface,
// R = C_phi phi + C_E (-D d phi / dn) (d'Eon 2012; d'Eon & Irving 2011, exitance):
// C_phi = (1 - 2 C_1) / 4, C_E = (1 - 3 C_2) / 2. With the P1 radiance
// L = phi / 4 pi + 3 E.w / 4 pi (Bitterli eq. 2.19), the power transmitted outward is
// 2 pi int_0^1 (1 - F_r) L mu dmu = phi (1 - 2 C_1) / 4 + E (1 - 3 C_2) / 2.
double exitance_fluence_weight(double eta);  // C_phi
double exitance_flux_weight(double eta);     // C_E

}  // namespace scatterlab
