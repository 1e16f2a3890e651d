#pragma once
// Classical diffusion for an isotropic point source of unit power in an infinite medium that
// scatters isotropically (g = 0), albedo c, lengths in mean free paths (sigma_t = 1): the
// diffusion Green's function (Bitterli eq. 2.25; d'Eon & Irving 2011, classical diffusion)
//   phi(rho) = exp(-sigma_tr rho) / (4 pi D rho),  sigma_tr = sqrt(sigma_a / D),
// with the classical, absorption-independent D = 1 / (3 sigma_t') = 1/3 (Bitterli eq. 2.22;
// sigma_t' = sigma_t for g = 0), so sigma_tr = sqrt(3 (1 - c)). It approximates the total
// fluence, uncollided light included, and conserves power: int phi 4 pi rho^2 drho = 1 / (1 - c),
// the exact number of collisions per source photon. (The absorption-dependent
// D = (2 sigma_a + sigma_s) / 3 belongs to Grosjean's approximation, point_source_grosjean.hpp.)
//
// Units as models/point_source_exact.hpp: fluence in mfp^-2 per unit source power.
// Limits: phi ~ 3 / (4 pi rho) as rho -> 0, so the point value needs rho > 0 (InputError "rho");
// shell integrals and averages are finite down to rho0 = 0. Albedo in [0, 1) (InputError
// "albedo"); c = 0 is allowed (phi = 3 exp(-sqrt 3 rho) / (4 pi rho), a poor approximation there
// by construction — that is what d'Eon & Irving's comparison shows).

namespace scatterlab {

// sigma_tr = sqrt(3 (1 - c)), 1 / mfp.
double diffusion_decay_rate(double albedo);

double diffusion_point_source_fluence(double albedo, double rho);

// 4 pi int_rho0^rho1 rho^2 phi drho (0 <= rho0 < rho1 < inf), in mfp per unit power.
double diffusion_point_source_shell_integral(double albedo, double rho0, double rho1);

// The shell integral divided by the shell volume 4/3 pi (rho1^3 - rho0^3).
double diffusion_point_source_shell_average(double albedo, double rho0, double rho1);

}  // namespace scatterlab
