#pragma once
// A Grosjean-based model of the searchlight problem: the pencil beam's first collisions along
// the axis are a line of isotropic sources, each treated as Grosjean treats a point source in
// an infinite medium (models/point_source_grosjean.hpp; d'Eon & Irving 2011 use the same
// extended source with Grosjean's diffusion coefficient), and the diffusion part is bounded by
// the better dipole's image about the extrapolated boundary (d'Eon 2012). Reduced coefficients
// throughout (similarity relations, Bitterli eqs. 2.23-2.24), so the model is exact in the
// split but approximate in the phase function for g != 0.
//
// Per unit power entering the medium, first collisions at depth z' have density
// sigma_t' exp(-sigma_t' z') and re-emit alpha' of it. A unit isotropic emission at (0, z')
// contributes to the fluence at distance d (and d_v from its image at -(z' + 2 z_b))
//   once scattered:  exp(-sigma_t' d) / (4 pi d^2)   (a straight path inside a half-space
//                    never crosses the surface, so this is exact for eta = 1),
//   multiply:        alpha' / (4 pi D) [exp(-sigma_tr d) / d - exp(-sigma_tr d_v) / d_v],
//   D = (2 sigma_a + sigma_s') / (3 sigma_t'^2), sigma_tr = sqrt(sigma_a / D), z_b = 2 A D with
//   the better dipole's A, and the uncollided beam adds exp(-sigma_t' z) on the axis (a line:
//   it shows up only in cell averages of cells on the axis).
// Exitance at the surface: the multiply-scattered part as the better dipole's,
// C_phi phi + C_E E; the once-scattered part is its flux through the surface,
// z' exp(-sigma_t' d) / (4 pi d^3), times 1 - F_dr(eta), an angle-averaged transmittance (the
// exact once-scattered exitance with the Fresnel factor per direction is the refractive solver's
// job; at eta = 1 this is exact up to F_dr(1) = 0.0016 of the Egan-Hilgeman fit).
//
// Units as models/dipole.hpp (per unit power entering the medium; lengths in the medium's unit).
// Limits: R_d(r) ~ alpha' (1 - F_dr) / (4 pi r) as r -> 0 (the once-scattered light near the
// entry point), so R_d(0) = +infinity; phi(0, z) = +infinity on the axis. Annulus and cell
// averages are finite everywhere, and so is the total.
//
// Known limitation: the once-scattered light that leaves through the surface is counted once
// as exitance and again as a source of the diffusion part (Grosjean's kernel assumes an infinite
// medium, where all of it collides again); the image removes only part of it. So R_dr exceeds
// the physical bound as alpha' -> 1: 1.15 at alpha' = 1, eta = 1 (the dipoles give 1.0).
//
// Cost: a point value is one adaptive quadrature over z'; a cell average of the fluence is a
// nested one (z outside, z' inside), about 1 ms per cell.

#include <span>
#include <vector>

#include "scatterlab/models/dipole.hpp"
#include "scatterlab/models/half_space_medium.hpp"

namespace scatterlab {

struct GrosjeanHalfSpace {
  double sigma_t = 1.0;         // sigma_t', 1 / length
  double albedo = 0.0;          // alpha'
  double diffusion = 0.0;       // D, length
  double sigma_tr = 0.0;        // 1 / length
  double boundary_height = 0.0;  // z_b = 2 A D, length
  double fluence_weight = 0.25;  // C_phi
  double flux_weight = 0.5;      // C_E
  double single_transmittance = 1.0;  // 1 - F_dr
};

GrosjeanHalfSpace grosjean_half_space(const HalfSpaceMedium& medium);

double grosjean_half_space_reflectance(const GrosjeanHalfSpace& model, double r);
double grosjean_half_space_fluence(const GrosjeanHalfSpace& model, double r, double z);
double grosjean_half_space_total_reflectance(const GrosjeanHalfSpace& model);
std::vector<double> grosjean_half_space_reflectance_annulus_average(
    const GrosjeanHalfSpace& model, std::span<const double> r_edges);
// Row-major [r][z]; the uncollided beam included in cells with r0 = 0.
std::vector<double> grosjean_half_space_fluence_cell_average(const GrosjeanHalfSpace& model,
                                                             std::span<const double> r_edges,
                                                             std::span<const double> z_edges);

}  // namespace scatterlab
