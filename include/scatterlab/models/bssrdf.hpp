#pragma once
// The diffusion BSSRDF from a radial profile (Bitterli eq. 2.16; Jensen et al. 2001):
//
//   S_d(x_i, w_i; x_o, w_o) = (1 / pi) F_t(eta, w_i) R_d(|x_o - x_i|) F_t(eta, w_o) / (4
//   C_phi(1/eta))
//
// F_t is the exact dielectric Fresnel transmittance (core/fresnel.hpp) at the angle outside the
// medium; 4 C_phi(1/eta) = 1 - 2 C_1(1/eta) is the published normalisation (d'Eon & Irving's
// moment fit, boundary_reflection.hpp): the hemispherical cosine-weighted average of F_t seen
// from outside. It makes the exitance of S_d, int S_d cos(theta_o) dw_o, equal to the profile's
// R_d up to the fit: that factor, exit_transmittance_ratio, is the exact average over the fitted
// one (1.000-1.006 for eta in [0.5, 2.5]). Without the normalisation (1/pi alone, as Jensen et al.
// print it) the exit Fresnel loss, which R_d already carries, would be counted twice.
//
// Units: S_d in 1 / (length^2 sr) per unit power entering at x_i from w_i (R_d's units over sr).
// Radiance leaving x_o is L_o = int_A int S_d L_i cos(theta_i) dw_i dA (Bitterli eq. 2.14).

#include <string>

#include "scatterlab/models/diffusion_profile.hpp"

namespace scatterlab {

// The exit term evaluates d'Eon & Irving's moment fits, which hold for indices in [0.5, 2.5]
// (boundary_reflection.hpp), at 1 / eta: so S_d takes eta in [0.5, 2]. Throws InputError
// naming `field` otherwise; a caller checks before its loops, whose threads cannot throw.
void check_bssrdf_eta(double eta, const std::string& field);

// F_t(eta, w_o) / (pi 4 C_phi(1/eta)): S_d's factor for the direction it leaves in, 1 / sr.
// cos_outside in [0, 1] is the cosine to the normal outside the medium.
double bssrdf_exit_weight(double eta, double cos_outside);

// S_d for an entry and an exit cosine (outside, in [0, 1]) and a distance r >= 0.
double bssrdf(const DiffusionProfile& profile, double r, double cos_in, double cos_out);

// 2 int_0^1 F_t(eta, mu) mu dmu (exact, by quadrature) over 1 - 2 C_1(1/eta) (the fit): the
// exitance of S_d per unit R_d.
double exit_transmittance_ratio(double eta);

}  // namespace scatterlab
