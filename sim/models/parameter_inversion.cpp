#include "scatterlab/models/parameter_inversion.hpp"

#include <cmath>

#include "scatterlab/core/error.hpp"
#include "scatterlab/models/dipole.hpp"
#include "scatterlab/models/grosjean_beam.hpp"
#include "scatterlab/models/quantized_diffusion.hpp"

namespace scatterlab {
namespace {

// The medium with sigma_t' = 1 and the given reduced albedo (g = 0: reduced = plain).
HalfSpaceMedium unit_medium(double reduced_albedo, double eta) {
  return HalfSpaceMedium{1.0 - reduced_albedo, reduced_albedo, 0.0, eta};
}

}  // namespace

std::string to_string(HalfSpaceModel model) {
  switch (model) {
    case HalfSpaceModel::classical_dipole: return "dipole";
    case HalfSpaceModel::better_dipole: return "better_dipole";
    case HalfSpaceModel::quantized_diffusion: return "quantized_diffusion";
    case HalfSpaceModel::grosjean_beam: return "scatterlab_grosjean_beam";
  }
  return "dipole";
}

HalfSpaceModel half_space_model_from_string(const std::string& name, const std::string& field) {
  std::string accepted;
  for (const HalfSpaceModel model : all_half_space_models) {
    if (to_string(model) == name) return model;
    accepted += (accepted.empty() ? "" : ", ") + to_string(model);
  }
  throw InputError(field, "got \"" + name + "\"", "one of " + accepted);
}

double total_diffuse_reflectance(HalfSpaceModel model, double reduced_albedo, double eta) {
  if (!(reduced_albedo >= 0.0 && reduced_albedo <= 1.0)) {
    throw InputError("reduced_albedo", "got " + std::to_string(reduced_albedo), "a number in [0, 1]");
  }
  const HalfSpaceMedium medium = unit_medium(reduced_albedo, eta);
  switch (model) {
    case HalfSpaceModel::classical_dipole: return dipole_total_reflectance(classical_dipole(medium));
    case HalfSpaceModel::better_dipole: return dipole_total_reflectance(better_dipole(medium));
    case HalfSpaceModel::quantized_diffusion:
      return quantized_diffusion_total_reflectance(quantized_diffusion(medium));
    case HalfSpaceModel::grosjean_beam:
      return grosjean_beam_total_reflectance(grosjean_beam(medium), ModelPart::all);
  }
  return 0.0;
}

double transport_to_extinction_ratio(HalfSpaceModel model, double reduced_albedo) {
  const double absorbed = 1.0 - reduced_albedo;
  if (model == HalfSpaceModel::classical_dipole) return std::sqrt(3.0 * absorbed);
  return std::sqrt(3.0 * absorbed / (2.0 - reduced_albedo));
}

InvertedCoefficients invert_reflectance(HalfSpaceModel model, double total_reflectance,
                                        double diffuse_mean_free_path, double eta, double g) {
  if (!(diffuse_mean_free_path > 0.0) || !std::isfinite(diffuse_mean_free_path)) {
    throw InputError("l_d", "got " + std::to_string(diffuse_mean_free_path), "a finite number > 0");
  }
  if (!(std::abs(g) < 1.0)) throw InputError("g", "got " + std::to_string(g), "|g| < 1");
  const double highest = total_diffuse_reflectance(model, 1.0, eta);
  if (!(total_reflectance > 0.0 && total_reflectance < highest)) {
    throw InputError("R_dr", "got " + std::to_string(total_reflectance),
                     "a number in (0, " + std::to_string(highest) + "), what " + to_string(model) +
                         " reaches at eta = " + std::to_string(eta));
  }
  // Bisection (Bitterli §3.4): R_dr(lo) < target <= R_dr(hi).
  double lo = 0.0, hi = 1.0;
  while (hi - lo > 1e-13) {
    const double mid = 0.5 * (lo + hi);
    (total_diffuse_reflectance(model, mid, eta) < total_reflectance ? lo : hi) = mid;
  }
  InvertedCoefficients result;
  result.reduced_albedo = 0.5 * (lo + hi);
  const double sigma_t_reduced =
      1.0 / (diffuse_mean_free_path * transport_to_extinction_ratio(model, result.reduced_albedo));
  const double sigma_s_reduced = result.reduced_albedo * sigma_t_reduced;  // Bitterli eq. 3.4
  result.sigma_a = sigma_t_reduced - sigma_s_reduced;                       // Bitterli eq. 3.5
  result.sigma_s = sigma_s_reduced / (1.0 - g);
  return result;
}

}  // namespace scatterlab
