#pragma once
// Grosjean's approximation for an isotropic point source of unit power in an infinite medium
// with isotropic scattering (g = 0), albedo c, lengths in mfp (sigma_t = 1), as used by d'Eon &
// Irving 2011 (quantized diffusion, the modified diffusion of Grosjean 1956): the uncollided
// fluence is kept exactly and only the collided part is approximated by diffusion,
//   phi(rho) = exp(-rho) / (4 pi rho^2) + c exp(-sigma_tr rho) / (4 pi D rho),
//   D = (2 sigma_a + sigma_s) / (3 sigma_t^2) = (2 - c) / 3,   sigma_tr = sqrt((1 - c) / D).
// Why this D (the derivation, checked by tests/unit/test_point_source_models.cpp): the exact
// collided fluence has Fourier transform c A^2 / (1 - c A), A = arctan(k) / k = 1 - k^2 / 3 + ...
// (point_source_exact.cpp, D2), so its volume integral is c / (1 - c) and its second moment
// int rho^2 phi dV over the integral is 2 (2 - c) / (1 - c). The diffusion kernel
// S exp(-sigma_tr rho) / (4 pi D rho) has transform S / (D (k^2 + sigma_tr^2)), integral
// S / (1 - c) and second moment ratio 6 D / (1 - c): both match for S = c and D = (2 - c) / 3.
// The same D is the better dipole's (d'Eon 2012), with reduced coefficients.
//
// Units as models/point_source_exact.hpp. Limits: the point value needs rho > 0 (the uncollided
// term goes as 1 / rho^2); shell integrals and averages are finite down to rho0 = 0.
// Albedo in [0, 1) (InputError "albedo"); at c = 0 the approximation is exact (uncollided only).

namespace scatterlab {

// sigma_tr = sqrt(3 (1 - c) / (2 - c)), 1 / mfp.
double grosjean_decay_rate(double albedo);

double grosjean_point_source_fluence(double albedo, double rho, bool include_uncollided = true);

// 4 pi int_rho0^rho1 rho^2 phi drho (0 <= rho0 < rho1 <= inf).
double grosjean_point_source_shell_integral(double albedo, double rho0, double rho1,
                                            bool include_uncollided = true);

// The shell integral over the shell volume (rho1 finite).
double grosjean_point_source_shell_average(double albedo, double rho0, double rho1,
                                           bool include_uncollided = true);

}  // namespace scatterlab
