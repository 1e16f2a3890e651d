#include "scatterlab/refract/half_space_single_scatter.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/phase_function.hpp"

namespace scatterlab {
namespace {

// Depth beyond which exp(-sigma_t z) < 1e-18 of the entering power: truncation far below any
// quadrature tolerance asked for.
constexpr double depth_cutoff_mfp = 41.5;

struct Setup {
  double sigma_t, sigma_s, entry_transmittance, eta;
  double critical_angle;  // exit possible for theta_i < critical_angle
  HenyeyGreenstein phase;

  // Light per unit solid angle at V that leaves, for exit angle theta: p T(theta) times the
  // attenuation of the inside path z / cos theta.
  double exit_kernel(double z, double theta) const {
    const double c = std::cos(theta);
    if (!(c > 0.0)) return 0.0;
    return phase.evaluate(-c) * fresnel_dielectric_transmittance(c, 1.0 / eta) *
           std::exp(-sigma_t * z / c);
  }
  double source(double z) const { return sigma_s * entry_transmittance * std::exp(-sigma_t * z); }
};

Setup make_setup(const Medium& medium, double eta) {
  medium.validate();
  if (!(eta > 0.0) || !std::isfinite(eta)) {
    throw InputError("eta", fmt::format("got {}", eta), "a finite number > 0");
  }
  Setup s{medium.sigma_t, medium.sigma_s(), fresnel_dielectric_transmittance(1.0, eta), eta,
          eta > 1.0 ? std::asin(1.0 / eta) : 0.5 * pi, HenyeyGreenstein{medium.g}};
  return s;
}

}  // namespace

SingleScatterReflectance half_space_single_scatter_reflectance(const Medium& medium, double eta,
                                                               std::span<const double> r_edges,
                                                               double rel_tol) {
  const Setup s = make_setup(medium, eta);
  if (r_edges.size() < 2) throw InputError("r_edges", "fewer than two edges", "two or more");
  for (std::size_t i = 0; i < r_edges.size(); ++i) {
    if (!(r_edges[i] >= 0.0) || !std::isfinite(r_edges[i]) ||
        (i > 0 && !(r_edges[i] > r_edges[i - 1]))) {
      throw InputError("r_edges", fmt::format("edge {} is {}", i, r_edges[i]),
                       "finite, non-negative, increasing values");
    }
  }
  const QuadratureOptions options{0.0, rel_tol, 400};

  // The annuli are independent: one thread each, so the figures do not depend on the thread count.
  const std::size_t bins = r_edges.size() - 1;
  SingleScatterReflectance result;
  result.mean.resize(bins);
  result.error.resize(bins);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::size_t bin = 0; bin < bins; ++bin) {
    const double r0 = r_edges[bin], r1 = r_edges[bin + 1];
    // Power leaving through the annulus, per unit exit angle (header: the depth integral done in
    // closed form). With k = sigma_t (1 + 1/c) and z_i = r_i / tan theta,
    //   int_z0^z1 exp(-k z) dz = exp(-k z0) (1 - exp(-k (z1 - z0))) / k,
    // and k z_i = sigma_t r_i (1 + c) / sin theta; the expm1 keeps thin annuli's digits.
    const auto per_angle = [&](double theta) {
      const double sin_t = std::sin(theta), c = std::cos(theta);
      if (!(sin_t > 0.0) || !(c > 0.0)) return 0.0;
      const double steepness = s.sigma_t * (1.0 + c) / sin_t;  // k / tan theta
      const double depth_share = std::exp(-steepness * r0) * -std::expm1(-steepness * (r1 - r0)) *
                                 c / (s.sigma_t * (1.0 + c));
      return 2.0 * pi * sin_t * s.exit_kernel(0.0, theta) * s.source(0.0) * depth_share;
    };
    const QuadratureResult q = integrate_adaptive(per_angle, 0.0, s.critical_angle, options);
    const double area = pi * (r1 * r1 - r0 * r0);
    result.mean[bin] = q.value / area;
    result.error[bin] = q.error / area;
  }
  // Over all r the depth integral is exact: int sigma_s T_in exp(-sigma_t z (1 + 1/c)) dz =
  // albedo T_in c / (1 + c), leaving one integral over the exit angle.
  const QuadratureResult total = integrate_adaptive(
      [&](double theta) {
        const double c = std::cos(theta);
        return 2.0 * pi * std::sin(theta) * s.exit_kernel(0.0, theta) * medium.albedo *
               s.entry_transmittance * c / (1.0 + c);
      },
      0.0, s.critical_angle, QuadratureOptions{0.0, 0.1 * rel_tol, 200});
  result.total = total.value;
  result.total_error = total.error;
  return result;
}

QuadratureResult half_space_single_scatter_exitance(const Medium& medium, double eta, double r,
                                                    double rel_tol) {
  const Setup s = make_setup(medium, eta);
  if (!(r > 0.0) || !std::isfinite(r)) {
    throw InputError("r", fmt::format("got {}", r), "a finite radius > 0");
  }
  // Exit needs tan theta_i = r / z below tan(critical angle).
  const double z_min = eta > 1.0 ? r / std::tan(s.critical_angle) : 0.0;
  const double z_max = z_min + depth_cutoff_mfp / s.sigma_t;
  const auto integrand = [&](double z) {
    if (!(z > 0.0)) return 0.0;
    const double theta = std::atan2(r, z);
    const double c = std::cos(theta);
    return s.source(z) * s.exit_kernel(z, theta) * c * c * c / (z * z);
  };
  std::vector<double> breaks{z_min, z_max};
  for (const double candidate : {r, z_min + 1.0 / s.sigma_t}) {
    if (candidate > z_min && candidate < z_max) breaks.push_back(candidate);
  }
  std::sort(breaks.begin(), breaks.end());
  return integrate_adaptive(integrand, breaks, QuadratureOptions{0.0, rel_tol, 400});
}

}  // namespace scatterlab
