#include "scatterlab/models/chandrasekhar_h.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/quadrature.hpp"

namespace scatterlab {
namespace {

// 1 - theta cot theta without cancellation: its Taylor series below 0.1 (terms to theta^10,
// truncation < 1e-16 relative), the direct form above, where the difference keeps 13 digits.
double one_minus_theta_cot_theta(double theta) {
  if (theta < 0.1) {
    const double t2 = theta * theta;
    return t2 * (1.0 / 3.0 + t2 * (1.0 / 45.0 + t2 * (2.0 / 945.0 +
                                                      t2 * (1.0 / 4725.0 + t2 * (2.0 / 93555.0)))));
  }
  return 1.0 - theta * std::cos(theta) / std::sin(theta);
}

void check_albedo(double albedo) {
  if (!(albedo >= 0.0 && albedo <= 1.0)) {
    throw InputError("albedo", fmt::format("got {}", albedo), "a number in [0, 1]");
  }
}

}  // namespace

double chandrasekhar_h(double albedo, double mu) {
  check_albedo(albedo);
  if (!(mu >= 0.0 && mu <= 1.0)) {
    throw InputError("mu", fmt::format("got {}", mu), "a cosine in [0, 1]");
  }
  if (albedo == 0.0 || mu == 0.0) return 1.0;
  // 1 - w theta cot theta = (1 - w) + w (1 - theta cot theta): both terms >= 0.
  const auto integrand = [albedo, mu](double theta) {
    const double s = std::sin(theta), c = std::cos(theta);
    const double characteristic = (1.0 - albedo) + albedo * one_minus_theta_cot_theta(theta);
    return std::log(characteristic) / (c * c + mu * mu * s * s);
  };
  QuadratureOptions options;
  options.rel_tol = 1e-13;
  const double integral = integrate_adaptive(integrand, 0.0, 0.5 * std::numbers::pi, options).value;
  return std::exp(-mu / std::numbers::pi * integral);
}

double half_space_diffuse_reflectance(double albedo, double mu0) {
  check_albedo(albedo);
  return 1.0 - chandrasekhar_h(albedo, mu0) * std::sqrt(1.0 - albedo);
}

}  // namespace scatterlab
