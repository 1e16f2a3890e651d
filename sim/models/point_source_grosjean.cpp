#include "scatterlab/models/point_source_grosjean.hpp"

#include <cmath>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/models/point_source_exact.hpp"
#include "shell_moment.hpp"

namespace scatterlab {
namespace {

// D = (2 sigma_a + sigma_s) / (3 sigma_t^2) with sigma_t = 1 (header: moment matching).
double grosjean_diffusion(double albedo) { return (2.0 - albedo) / 3.0; }

}  // namespace

double grosjean_decay_rate(double albedo) {
  detail::check_point_source_albedo(albedo);
  return std::sqrt((1.0 - albedo) / grosjean_diffusion(albedo));
}

double grosjean_point_source_fluence(double albedo, double rho, bool include_uncollided) {
  const double s = grosjean_decay_rate(albedo);
  detail::check_point_source_rho(rho);
  const double collided =
      albedo * std::exp(-s * rho) * inv_four_pi / (grosjean_diffusion(albedo) * rho);
  return include_uncollided ? point_source_fluence_uncollided(rho) + collided : collided;
}

double grosjean_point_source_shell_integral(double albedo, double rho0, double rho1,
                                            bool include_uncollided) {
  const double s = grosjean_decay_rate(albedo);
  detail::check_shell(rho0, rho1, true);
  const double collided =
      albedo * detail::linear_exponential_moment(s, rho0, rho1) / grosjean_diffusion(albedo);
  if (!include_uncollided) return collided;
  // The exact solution at c = 0 is the uncollided fluence alone.
  return point_source_fluence_shell_integral(0.0, rho0, rho1) + collided;
}

double grosjean_point_source_shell_average(double albedo, double rho0, double rho1,
                                           bool include_uncollided) {
  if (!std::isfinite(rho1)) detail::check_shell(rho0, rho1, false);
  const double integral = grosjean_point_source_shell_integral(albedo, rho0, rho1, include_uncollided);
  return integral / (4.0 / 3.0 * pi * (rho1 - rho0) * (rho1 * rho1 + rho1 * rho0 + rho0 * rho0));
}

}  // namespace scatterlab
