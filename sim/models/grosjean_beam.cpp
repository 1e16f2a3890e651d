#include "scatterlab/models/grosjean_half_space.hpp"

#include <algorithm>
#include <functional>
#include <cmath>
#include <string>
#include <vector>

#include "radial_integrals.hpp"
#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/quadrature.hpp"
#include "scatterlab/models/boundary_reflection.hpp"

namespace scatterlab {
namespace {

// Depth beyond which the first-collision density exp(-sigma_t' z') < exp(-50) ~ 2e-22.
constexpr double depth_cutoff_mfp = 50.0;

// The multiply-scattered part of a unit emission at depth z': the better dipole's point source
// and image, moved to z' (header).
DipoleModel emission_dipole(const GrosjeanHalfSpace& m, double depth) {
  DipoleModel dipole;
  dipole.strength = m.albedo;
  dipole.diffusion = m.diffusion;
  dipole.sigma_tr = m.sigma_tr;
  dipole.source_depth = depth;
  dipole.image_height = depth + 2.0 * m.boundary_height;
  dipole.fluence_weight = m.fluence_weight;
  dipole.flux_weight = m.flux_weight;
  return dipole;
}

// Power re-emitted per unit depth by first collisions at z', per unit power entering.
double emission_density(const GrosjeanHalfSpace& m, double depth) {
  return m.sigma_t * m.albedo * std::exp(-m.sigma_t * depth);
}

// Breakpoints on [0, cutoff]: the integrand over z' has features of width ~`width` around
// `centre` (the point's depth, or the surface for reflectance), and decays on 1 / sigma_t'.
std::vector<double> depth_breaks(const GrosjeanHalfSpace& m, double centre, double width) {
  const double cutoff = depth_cutoff_mfp / m.sigma_t;
  std::vector<double> breaks{0.0, cutoff, 1.0 / m.sigma_t, 5.0 / m.sigma_t, centre};
  for (const double f : {0.25, 1.0, 4.0}) {
    breaks.push_back(centre - f * width);
    breaks.push_back(centre + f * width);
  }
  std::erase_if(breaks, [cutoff](double b) { return !(b >= 0.0 && b <= cutoff); });
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  return breaks;
}

double integrate(const std::function<double(double)>& f, std::span<const double> breaks,
                 double rel_tol) {
  QuadratureOptions options;
  options.rel_tol = rel_tol;
  options.abs_tol = 1e-300;
  return integrate_adaptive(f, breaks, options).value;
}

// int_r0^r1 2 pi r z' exp(-s d) / (4 pi d^3) dr = z' / 2 int_d0^d1 exp(-s d) / d^2 dd
// = z' / 2 [exp(-s d0) / d0 - exp(-s d1) / d1 - s (E_1(s d0) - E_1(s d1))] (integration by
// parts; A&S 5.1.1 for E_1). Tends to 1/2 (r0 = 0) or 0 (r0 > 0) as z' -> 0.
double single_exit_annulus(double s, double depth, double r0, double r1) {
  if (depth == 0.0) return r0 == 0.0 ? 0.5 : 0.0;
  const double d0 = std::hypot(r0, depth), d1 = std::hypot(r1, depth);
  return 0.5 * depth *
         (std::exp(-s * d0) / d0 - std::exp(-s * d1) / d1 - s * detail::exp_over_d_integral(s, d0, d1));
}

void check_r(double r) {
  if (!(r >= 0.0) || !std::isfinite(r)) {
    throw InputError("r", "got " + std::to_string(r), "a finite number >= 0");
  }
}

}  // namespace

GrosjeanHalfSpace grosjean_half_space(const HalfSpaceMedium& medium) {
  medium.validate();
  GrosjeanHalfSpace m;
  m.sigma_t = medium.reduced_sigma_t();
  m.albedo = medium.reduced_albedo();
  // Grosjean's D with reduced coefficients (point_source_grosjean.hpp; d'Eon 2012).
  m.diffusion = (2.0 * medium.sigma_a + medium.reduced_sigma_s()) / (3.0 * m.sigma_t * m.sigma_t);
  m.sigma_tr = std::sqrt(medium.sigma_a / m.diffusion);
  m.boundary_height = 2.0 * better_boundary_a(medium.eta) * m.diffusion;  // Bitterli §2.5
  m.fluence_weight = exitance_fluence_weight(medium.eta);
  m.flux_weight = exitance_flux_weight(medium.eta);
  m.single_transmittance = 1.0 - diffuse_fresnel_reflectance(medium.eta);
  return m;
}

double grosjean_half_space_reflectance(const GrosjeanHalfSpace& m, double r) {
  check_r(r);
  if (m.albedo == 0.0) return 0.0;
  if (r == 0.0) return HUGE_VAL;  // ~ alpha' (1 - F_dr) / (4 pi r)
  const auto integrand = [&](double depth) {
    const double d = std::hypot(r, depth);
    const double single =
        m.single_transmittance * depth * std::exp(-m.sigma_t * d) * inv_four_pi / (d * d * d);
    return emission_density(m, depth) * (single + dipole_reflectance(emission_dipole(m, depth), r));
  };
  const auto breaks = depth_breaks(m, 0.0, r);
  return integrate(integrand, breaks, 1e-9);
}

double grosjean_half_space_fluence(const GrosjeanHalfSpace& m, double r, double z) {
  check_r(r);
  if (!(z >= 0.0) || !std::isfinite(z)) {
    throw InputError("z", "got " + std::to_string(z), "a finite depth >= 0 (inside the medium)");
  }
  if (m.albedo == 0.0) return 0.0;  // off the axis nothing but scattered light
  if (r == 0.0) return HUGE_VAL;
  const auto integrand = [&](double depth) {
    const double d = std::hypot(r, z - depth);
    const double single = std::exp(-m.sigma_t * d) * inv_four_pi / (d * d);
    return emission_density(m, depth) * (single + dipole_fluence(emission_dipole(m, depth), r, z));
  };
  const auto breaks = depth_breaks(m, z, r);
  return integrate(integrand, breaks, 1e-9);
}

double grosjean_half_space_total_reflectance(const GrosjeanHalfSpace& m) {
  if (m.albedo == 0.0) return 0.0;
  const auto integrand = [&](double depth) {
    // single_exit_annulus over [0, inf): (exp(-s z') - s z' E_1(s z')) / 2.
    const double x = m.sigma_t * depth;
    const double single =
        depth == 0.0 ? 0.5 : 0.5 * (std::exp(-x) - x * detail::exponential_integral_e1(x));
    return emission_density(m, depth) *
           (m.single_transmittance * single + dipole_total_reflectance(emission_dipole(m, depth)));
  };
  const auto breaks = depth_breaks(m, 0.0, 1.0 / m.sigma_t);
  return integrate(integrand, breaks, 1e-10);
}

std::vector<double> grosjean_half_space_reflectance_annulus_average(
    const GrosjeanHalfSpace& m, std::span<const double> r_edges) {
  detail::check_edges(r_edges, "r_edges");
  std::vector<double> average(r_edges.size() - 1, 0.0);
  if (m.albedo == 0.0) return average;
  for (std::size_t i = 0; i + 1 < r_edges.size(); ++i) {
    const double r0 = r_edges[i], r1 = r_edges[i + 1];
    const auto integrand = [&](double depth) {
      return emission_density(m, depth) *
             (m.single_transmittance * single_exit_annulus(m.sigma_t, depth, r0, r1) +
              dipole_reflectance_annulus_integral(emission_dipole(m, depth), r0, r1));
    };
    const auto breaks = depth_breaks(m, 0.0, r1);
    average[i] = integrate(integrand, breaks, 1e-9) / (pi * (r1 * r1 - r0 * r0));
  }
  return average;
}

std::vector<double> grosjean_half_space_fluence_cell_average(const GrosjeanHalfSpace& m,
                                                             std::span<const double> r_edges,
                                                             std::span<const double> z_edges) {
  detail::check_edges(r_edges, "r_edges");
  detail::check_edges(z_edges, "z_edges");
  const std::size_t nr = r_edges.size() - 1, nz = z_edges.size() - 1;
  std::vector<double> average(nr * nz, 0.0);
  const double s = m.sigma_t;
  for (std::size_t i = 0; i < nr; ++i) {
    const double r0 = r_edges[i], r1 = r_edges[i + 1];
    // int_r0^r1 2 pi r phi dr from a unit emission at z', seen at depth z.
    const auto radial = [&](double z, double depth) {
      const double d0 = std::max(std::hypot(r0, z - depth), 1e-300);
      const double d1 = std::hypot(r1, z - depth);
      // 2 pi int exp(-s d) / (4 pi d^2) r dr = 1/2 int exp(-s d) / d dd.
      const double single = 0.5 * detail::exp_over_d_integral(s, d0, d1);
      return single + dipole_fluence_annulus_integral(emission_dipole(m, depth), r0, r1, z);
    };
    for (std::size_t j = 0; j < nz; ++j) {
      const double z0 = z_edges[j], z1 = z_edges[j + 1];
      double integral = 0.0;
      if (m.albedo > 0.0) {
        const auto over_depth = [&](double z) {
          const auto breaks = depth_breaks(m, z, std::max(r1, 1e-3 / s));
          return integrate([&](double depth) { return emission_density(m, depth) * radial(z, depth); },
                           breaks, 1e-7);
        };
        const std::vector<double> z_breaks{z0, 0.5 * (z0 + z1), z1};
        integral = integrate(over_depth, z_breaks, 1e-6);
      }
      // The uncollided beam: int exp(-s z) dz over the cell, on the axis.
      if (r0 == 0.0) integral += std::exp(-s * z0) * -std::expm1(-s * (z1 - z0)) / s;
      average[i * nz + j] = integral / (pi * (r1 * r1 - r0 * r0) * (z1 - z0));
    }
  }
  return average;
}

}  // namespace scatterlab
