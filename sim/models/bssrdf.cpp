#include "scatterlab/models/bssrdf.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/quadrature.hpp"
#include "scatterlab/models/boundary_reflection.hpp"

namespace scatterlab {
namespace {

// 4 C_phi(1/eta) = 1 - 2 C_1(1/eta) (boundary_reflection.hpp: C_phi = (1 - 2 C_1) / 4).
double exit_normalisation(double eta) {
  return 4.0 * exitance_fluence_weight(1.0 / eta);
}

}  // namespace

void check_bssrdf_eta(double eta, const std::string& field) {
  if (!(eta >= 0.5 && eta <= 2.0)) {
    throw InputError(field, fmt::format("got {}", eta),
                     "a relative index of refraction in [0.5, 2] for the diffusion BSSRDF (its "
                     "exit term evaluates d'Eon & Irving's moment fits, valid in [0.5, 2.5], at "
                     "1 / eta)");
  }
}

double bssrdf_exit_weight(double eta, double cos_outside) {
  return fresnel_dielectric_transmittance(cos_outside, eta) /
         (std::numbers::pi * exit_normalisation(eta));
}

double bssrdf(const DiffusionProfile& profile, double r, double cos_in, double cos_out) {
  const double eta = profile.medium().eta;
  return fresnel_dielectric_transmittance(cos_in, eta) * profile.reflectance(r) *
         bssrdf_exit_weight(eta, cos_out);
}

double exit_transmittance_ratio(double eta) {
  // Light from outside meets no total reflection for eta >= 1; for eta < 1 it does beyond
  // mu = sqrt(1 - eta^2), where F_t has a kink: split there.
  std::vector<double> breaks{0.0, 1.0};
  if (eta < 1.0) breaks.insert(breaks.begin() + 1, std::sqrt(1.0 - eta * eta));
  const QuadratureResult average = integrate_adaptive(
      [eta](double mu) { return 2.0 * fresnel_dielectric_transmittance(mu, eta) * mu; }, breaks);
  return average.value / exit_normalisation(eta);
}

}  // namespace scatterlab
