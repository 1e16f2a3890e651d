#pragma once
// The artist's parametrisation of a half-space model, total diffuse reflectance R_dr and diffuse
// mean free path l_d = 1 / sigma_tr, inverted to (sigma_a, sigma_s) (Jensen & Buhler 2002;
// Bitterli §3.4). Every model's R_dr depends on the reduced albedo alpha' and eta only (lengths
// scale with 1 / sigma_t'), and rises monotonically from 0 at alpha' = 0, so alpha' is found by
// bisection on [0, 1] (Bitterli §3.4 chose bisection for its robustness across R_dr functions);
// then sigma_t' = sigma_tr / (sigma_tr / sigma_t')(alpha') with sigma_tr = 1 / l_d
// (Bitterli eqs. 3.3-3.5 for the classical dipole), sigma_s' = alpha' sigma_t',
// sigma_a = sigma_t' - sigma_s', and sigma_s = sigma_s' / (1 - g).
//
// Bad input is an InputError: "R_dr" outside (0, R_dr(alpha' -> 1)) (what the model can
// reach), "l_d" not a finite number > 0, "g" with |g| >= 1, "eta" outside [0.5, 2.5].

#include <string>

namespace scatterlab {

enum class HalfSpaceModel { classical_dipole, better_dipole, grosjean };

std::string to_string(HalfSpaceModel model);

// R_dr of the model for reduced albedo alpha' in [0, 1] and index eta (per unit power entering).
double total_diffuse_reflectance(HalfSpaceModel model, double reduced_albedo, double eta);

// sigma_tr / sigma_t' of the model: sqrt(3 (1 - alpha')) for the classical dipole
// (D = 1 / (3 sigma_t')), sqrt(3 (1 - alpha') / (2 - alpha')) with the better dipole's and
// Grosjean's D = (2 sigma_a + sigma_s') / (3 sigma_t'^2).
double transport_to_extinction_ratio(HalfSpaceModel model, double reduced_albedo);

struct InvertedCoefficients {
  double reduced_albedo = 0.0;  // alpha'
  double sigma_a = 0.0;         // 1 / (unit of l_d)
  double sigma_s = 0.0;         // 1 / (unit of l_d), for the given g
};

// alpha' to within 1e-13 (absolute).
InvertedCoefficients invert_reflectance(HalfSpaceModel model, double total_reflectance,
                                        double diffuse_mean_free_path, double eta, double g = 0.0);

}  // namespace scatterlab
