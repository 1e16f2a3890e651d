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

enum class HalfSpaceModel { classical_dipole, better_dipole, quantized_diffusion, grosjean_beam };

// Every model, in the order above.
inline constexpr HalfSpaceModel all_half_space_models[] = {
    HalfSpaceModel::classical_dipole, HalfSpaceModel::better_dipole,
    HalfSpaceModel::quantized_diffusion, HalfSpaceModel::grosjean_beam};

// The model's name in files and on the command line: "dipole", "better_dipole",
// "quantized_diffusion", "scatterlab_grosjean_beam" (the name says it is this project's
// construction, grosjean_beam.hpp).
std::string to_string(HalfSpaceModel model);

// The model named `name` (as to_string); InputError naming `field` and the accepted names.
HalfSpaceModel half_space_model_from_string(const std::string& name, const std::string& field);

// R_dr of the model for reduced albedo alpha' in [0, 1] and index eta (per unit power entering):
// the diffusion models' multiply-scattered light, the Grosjean beam's once and multiply
// scattered light together.
double total_diffuse_reflectance(HalfSpaceModel model, double reduced_albedo, double eta);

// sigma_tr / sigma_t' of the model: sqrt(3 (1 - alpha')) for the classical dipole
// (D = 1 / (3 sigma_t')), sqrt(3 (1 - alpha') / (2 - alpha')) with Grosjean's
// D = (2 sigma_a + sigma_s') / (3 sigma_t'^2) of the other three.
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
