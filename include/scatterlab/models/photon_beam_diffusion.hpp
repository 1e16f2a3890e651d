#pragma once
// Photon beam diffusion (Habel, Christensen & Jarosz 2013, "Photon Beam Diffusion: A Hybrid Monte
// Carlo Method for Subsurface Scattering", EGSR, Computer Graphics Forum 32(4)), for the
// searchlight problem at normal incidence: the better dipole (dipole.hpp) spread along the
// refracted beam instead of held at one depth, as renderers use it (pbrt-v3's BeamDiffusionMS and
// BeamDiffusionSS evaluate the same integrals with 100 exponential quantiles; here each is an
// adaptive quadrature to a stated tolerance).
//
// Multiply scattered light (the exitance of each source as PBD eq. 5, kappa as PBD eq. 12):
//   R_m(r) = int_0^inf Q(t) kappa(t, r) [C_phi phi_t(r) + C_E E_t(r)] dt,
//   Q(t)   = alpha' sigma_t' exp(-sigma_t' t)   (first collisions along the beam, per unit depth),
//   kappa  = 1 - exp(-2 sigma_t' (d_r + t)),  d_r = sqrt(r^2 + t^2)   (PBD eq. 12),
// where phi_t, E_t are the fluence and normal flux at the surface point r of a point source of
// strength alpha' at depth t with its image at height t + 4 A D (Grosjean's
// D = (2 sigma_a + sigma_s') / (3 sigma_t'^2), A = (1 + 3 C_2) / (1 - 2 C_1),
// C_phi = (1 - 2 C_1) / 4, C_E = (1 - 3 C_2) / 2: boundary_reflection.hpp). The strength alpha' of
// each source, times Q's alpha', is the alpha'^2 that dipole.hpp derives for Grosjean's D (pbrt-v3
// writes it rhop * rhop). kappa removes the diffusion light of sources so near the surface that
// the exact transport would send it out before it diffuses.
//
// Once scattered light (PBD's single-scattering term): the beam scatters at depth t toward the
// surface point at distance r, which it leaves with the exact dielectric transmittance:
//   R_s(r) = int_{t_c}^inf sigma_s exp(-sigma_t (t + d)) p(-t / d) T(t / d) (t / d) / d^2 dt,
// d = sqrt(r^2 + t^2), p the Henyey-Greenstein phase function of the real medium (not reduced),
// T = 1 - F_r leaving the medium, t_c = r sqrt(eta^2 - 1) below which the path meets total
// internal reflection (0 for eta <= 1). At normal incidence this is the exact once-scattered
// exitance (tests hold it against refract/half_space_single_scatter.hpp).
//
// Units as dipole.hpp: lengths in the medium's unit, R in 1 / length^2 per unit power entering.
// Normal incidence, eta in [0.5, 2.5] (the Fresnel-moment fits). Both parts are infinite at r = 0:
// near the entry point the source at depth t gives a normal flux ~ 1 / t^2 and kappa ~ 4 sigma_t' t
// takes only a factor t from it, so R_m(r) grows as log(1 / r); R_s(r) grows as 1 / r. Annulus
// averages and totals are finite.

#include <span>
#include <vector>

#include "scatterlab/models/dipole.hpp"
#include "scatterlab/models/half_space_medium.hpp"

namespace scatterlab {

struct PhotonBeamDiffusion {
  HalfSpaceMedium medium;
  double sigma_t_reduced = 1.0;  // sigma_t', 1 / length
  // The better dipole of one source at depth 0: strength alpha', D, sigma_tr, C_phi, C_E, and
  // image_height = 4 A D; photon_beam_diffusion_source moves it to depth t.
  DipoleModel source;
};

PhotonBeamDiffusion photon_beam_diffusion(const HalfSpaceMedium& medium);

// The dipole of first collisions at depth t >= 0 (strength alpha', kappa not applied).
DipoleModel photon_beam_diffusion_source(const PhotonBeamDiffusion& model, double depth);

// R_m(r) and R_s(r), r >= 0 (InputError "r" otherwise); relative quadrature error <= 1e-9.
double photon_beam_diffusion_reflectance(const PhotonBeamDiffusion& model, double r);
double photon_beam_diffusion_single(const PhotonBeamDiffusion& model, double r);

// R_dr of the multiply scattered part, int_0^inf R_m 2 pi r dr.
double photon_beam_diffusion_total_reflectance(const PhotonBeamDiffusion& model);
// int_r0^r1 R_m 2 pi r dr (0 <= r0 < r1, not checked).
double photon_beam_diffusion_annulus_integral(const PhotonBeamDiffusion& model, double r0,
                                              double r1);
// Averages of R_m over the annuli between consecutive edges (InputError "r_edges" when they are
// not finite, >= 0 and increasing).
std::vector<double> photon_beam_diffusion_annulus_average(const PhotonBeamDiffusion& model,
                                                          std::span<const double> r_edges);

}  // namespace scatterlab
