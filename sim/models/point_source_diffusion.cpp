#include "scatterlab/models/point_source_diffusion.hpp"

#include <cmath>
#include <string>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"
#include "shell_moment.hpp"

namespace scatterlab {
namespace {

constexpr double classical_diffusion = 1.0 / 3.0;  // D = 1 / (3 sigma_t'), Bitterli eq. 2.22

}  // namespace

double diffusion_decay_rate(double albedo) {
  detail::check_point_source_albedo(albedo);
  return std::sqrt((1.0 - albedo) / classical_diffusion);  // sigma_tr = sqrt(sigma_a / D)
}

double diffusion_point_source_fluence(double albedo, double rho) {
  const double s = diffusion_decay_rate(albedo);
  detail::check_point_source_rho(rho);
  return std::exp(-s * rho) * inv_four_pi / (classical_diffusion * rho);  // Bitterli eq. 2.25
}

double diffusion_point_source_shell_integral(double albedo, double rho0, double rho1) {
  const double s = diffusion_decay_rate(albedo);
  detail::check_shell(rho0, rho1, false);
  // 4 pi rho^2 exp(-s rho) / (4 pi D rho) = rho exp(-s rho) / D.
  return detail::linear_exponential_moment(s, rho0, rho1) / classical_diffusion;
}

double diffusion_point_source_shell_average(double albedo, double rho0, double rho1) {
  const double integral = diffusion_point_source_shell_integral(albedo, rho0, rho1);
  return integral / (4.0 / 3.0 * pi * (rho1 - rho0) * (rho1 * rho1 + rho1 * rho0 + rho0 * rho0));
}

}  // namespace scatterlab
