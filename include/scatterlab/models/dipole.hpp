#pragma once
// Dipole diffusion models of the searchlight problem (Bitterli §2.3-2.5): one isotropic point
// source at depth z_r = 1 / sigma_t' below the surface, and its negative image mirrored about
// the extrapolated boundary z = -z_b, z_b = 2 A D (method of images, Bitterli §2.5, eqs.
// 2.32-2.33). Two members of the family:
//
//   classical dipole (Jensen et al. 2001 §2.3-2.4; Bitterli eqs. 2.22, 2.30, 2.37):
//     strength alpha', D = 1 / (3 sigma_t'), A = (1 + F_dr) / (1 - F_dr) with the Egan-Hilgeman
//     F_dr, and R_d = the normal flux through the surface, -D dphi/dn (Bitterli eq. 2.21);
//   better dipole (d'Eon 2012, "A better dipole"; as printed by Vavassori §3.2.3):
//     strength alpha'^2, D = (2 sigma_a + sigma_s') / (3 sigma_t'^2),
//     A = (1 + 3 C_2) / (1 - 2 C_1), and R_d = C_phi phi + C_E (-D dphi/dn)
//     (boundary_reflection.hpp).
//
// Why alpha'^2 for the better dipole. Its D is Grosjean's (point_source_grosjean.hpp), and
// Grosjean's split of a unit isotropic emission keeps the uncollided light exact and models only
// the collided part, with strength c: c exp(-sigma_tr rho) / (4 pi D rho). The beam's first
// collision re-emits alpha' per unit power entering; the part of that emission that collides
// again carries another alpha'. So the diffusion term with Grosjean's D is the light scattered
// at least twice, of strength alpha'^2, and the once-scattered light is a separate term (the
// exact refractive single-scatter solution, refract/half_space_single_scatter.hpp). Vavassori
// §3.2.3 prints alpha'^2; d'Eon & Irving 2011 and photon beam diffusion (Habel et al. 2013)
// carry the same factor. The Monte Carlo settles it on the part whose definition matches, the
// light scattered at least twice (diffuse_reflectance_multiple), at g = 0 where reduced and plain
// orders coincide: 10^6 photons (3 10^5 at albedo 0.99), normal incidence, R_dr of the multiply-scattered part
//     albedo  eta   Monte Carlo        alpha'^2   alpha'
//     0.5     1.0   0.0387 +- 0.0002   0.0461     0.0921
//     0.9     1.0   0.2775 +- 0.0004   0.3441     0.3823
//     0.99    1.0   0.6015 +- 0.0009   0.7380     0.7455
//     0.5     1.3   0.0255 +- 0.0002   0.0284     0.0569
//     0.9     1.3   0.2192 +- 0.0004   0.2393     0.2659
//     0.99    1.3   0.5719 +- 0.0008   0.6311     0.6375
// alpha'^2 is the nearer everywhere; alpha' more than doubles the error at albedo 0.5. (The rest of
// the gap is the point source: the first collisions spread over depth, and the light that
// escapes after one scattering is still counted as a diffusion source. Quantized diffusion and
// the Grosjean beam (quantized_diffusion.hpp, grosjean_beam.hpp) address the first; the Grosjean
// beam the second.) The classical dipole keeps Jensen's alpha' with its absorption-independent D:
// that pair approximates all scattered light, as classical diffusion of a point source does
// (point_source_diffusion.hpp).
//
// Both share sigma_tr = sqrt(sigma_a / D), z_r = 1 / sigma_t', and the image at height
// z_v = z_r + 4 A D above the surface (Bitterli §2.5). With d_r, d_v the distances from (r, z)
// to the source (0, z_r) and the image (0, -z_v), Bitterli eq. 2.33 (times the strength) gives
//   phi(r, z) = strength / (4 pi D) [exp(-sigma_tr d_r) / d_r - exp(-sigma_tr d_v) / d_v],
// and -D dphi/dn at z = 0 (Bitterli eq. 2.37)
//   E(r) = strength / (4 pi) [z_r (1 + sigma_tr d_r) exp(-sigma_tr d_r) / d_r^3
//                            + z_v (1 + sigma_tr d_v) exp(-sigma_tr d_v) / d_v^3].
//
// Units: lengths in the medium's length unit; R_d in 1 / length^2 and phi in 1 / length^2, both
// per unit power that entered the medium (the entry Fresnel loss at the surface is not in them:
// multiply by the entry transmittance to compare with a tally per unit incident power).
//
// Limits: R_d is finite everywhere (d_r >= z_r > 0), including r = 0. phi is +infinity at the
// source point (r, z) = (0, z_r) and finite elsewhere; its cell averages are finite. At
// sigma_a = 0, sigma_tr = 0 and every formula keeps its sigma_tr -> 0 limit (R_dr -> strength = 1).
// At strength 0 everything is 0. Fluence is defined for z >= 0 (the medium) only.

#include <span>
#include <vector>

#include "scatterlab/models/half_space_medium.hpp"

namespace scatterlab {

struct DipoleModel {
  double strength = 0.0;        // alpha' or alpha'^2, power of the real source per unit entering
  double diffusion = 0.0;       // D, length
  double sigma_tr = 0.0;        // 1 / length
  double source_depth = 0.0;    // z_r, length
  double image_height = 0.0;    // z_v = z_r + 4 A D, length
  double fluence_weight = 0.0;  // C_phi (0 for the classical dipole)
  double flux_weight = 1.0;     // C_E (1 for the classical dipole)
};

DipoleModel classical_dipole(const HalfSpaceMedium& medium);
DipoleModel better_dipole(const HalfSpaceMedium& medium);

// Diffuse reflectance R_d(r) per unit area (r >= 0).
double dipole_reflectance(const DipoleModel& model, double r);

// Fluence phi(r, z) for r >= 0, z >= 0.
double dipole_fluence(const DipoleModel& model, double r, double z);

// R_dr = int_0^inf R_d(r) 2 pi r dr, in closed form (Bitterli eq. 3.1-3.2 for the classical
// dipole): strength / 2 [C_E (e_r + e_v) + C_phi / (D sigma_tr) (e_r - e_v)], e_x = exp(-sigma_tr z_x).
double dipole_total_reflectance(const DipoleModel& model);

// int_r0^r1 R_d 2 pi r dr and int_r0^r1 phi(r, z) 2 pi r dr, in closed form (0 <= r0 < r1, z >= 0;
// not checked: the building blocks of the averages below and of the Grosjean half-space model).
double dipole_reflectance_annulus_integral(const DipoleModel& model, double r0, double r1);
double dipole_fluence_annulus_integral(const DipoleModel& model, double r0, double r1, double z);

// Averages of R_d over the annuli between consecutive edges (int R_d 2 pi r dr / area), in
// closed form; edges finite, >= 0 and increasing (InputError "r_edges" otherwise).
std::vector<double> dipole_reflectance_annulus_average(const DipoleModel& model,
                                                      std::span<const double> r_edges);

// Averages of phi over the cells [r_i, r_i+1) x [z_j, z_j+1) (the r integral in closed form,
// the z integral by adaptive Gauss-Kronrod), row-major [r][z]; z edges >= 0.
std::vector<double> dipole_fluence_cell_average(const DipoleModel& model,
                                                std::span<const double> r_edges,
                                                std::span<const double> z_edges);

}  // namespace scatterlab
