#include "scatterlab/models/boundary_reflection.hpp"

#include <cmath>
#include <string>

#include "scatterlab/core/error.hpp"

namespace scatterlab {
namespace {

void check_eta(double eta) {
  if (!(eta >= 0.5 && eta <= 2.5)) {
    throw InputError("eta", "got " + std::to_string(eta),
                     "a relative index of refraction in [0.5, 2.5]");
  }
}

// c0 + c1 x + ... + c5 x^5 by Horner's rule.
double quintic(double x, double c0, double c1, double c2, double c3, double c4, double c5) {
  return c0 + x * (c1 + x * (c2 + x * (c3 + x * (c4 + x * c5))));
}

}  // namespace

double fresnel_moment1(double eta) {
  check_eta(eta);
  // d'Eon & Irving 2011, 2 C_1 fits, halved.
  if (eta < 1.0) {
    return quintic(eta, 0.45966, -1.73965, 3.37668, -3.904945, 2.49277, -0.68441);
  }
  return quintic(eta, -4.61686, 11.1136, -10.4646, 5.11455, -1.27198, 0.12746);
}

double fresnel_moment2(double eta) {
  check_eta(eta);
  // d'Eon & Irving 2011, 3 C_2 fits, divided by 3; for eta >= 1 the fit has terms in 1 / eta.
  if (eta < 1.0) {
    return quintic(eta, 0.27614, -0.87350, 1.12077, -0.65095, 0.07883, 0.04860);
  }
  const double inv = 1.0 / eta;
  return -547.033 + inv * (458.843 + inv * (-218.725 + inv * 45.3087)) +
         eta * (404.557 + eta * (-189.519 + eta * (54.9327 + eta * (-9.00603 + eta * 0.63942))));
}

double diffuse_fresnel_reflectance(double eta) {
  check_eta(eta);
  if (eta < 1.0) return 2.0 * fresnel_moment1(eta);
  // Egan & Hilgeman 1979 (Bitterli eq. 2.30).
  return -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
}

double classical_boundary_a(double eta) {
  const double f_dr = diffuse_fresnel_reflectance(eta);
  return (1.0 + f_dr) / (1.0 - f_dr);
}

double better_boundary_a(double eta) {
  return (1.0 + 3.0 * fresnel_moment2(eta)) / (1.0 - 2.0 * fresnel_moment1(eta));
}

double exitance_fluence_weight(double eta) { return 0.25 * (1.0 - 2.0 * fresnel_moment1(eta)); }

double exitance_flux_weight(double eta) { return 0.5 * (1.0 - 3.0 * fresnel_moment2(eta)); }

}  // namespace scatterlab
