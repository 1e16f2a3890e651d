#include "scatterlab/models/grosjean_beam.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "radial_integrals.hpp"
#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/quadrature.hpp"
#include "scatterlab/models/boundary_reflection.hpp"
#include "scatterlab/models/dipole.hpp"

namespace scatterlab {
namespace {

// Depth beyond which the first-collision density exp(-sigma_t' z') < exp(-50) ~ 2e-22.
constexpr double depth_cutoff_mfp = 50.0;
// Gauss-Legendre points of the escape probability's integral over mu.
constexpr int escape_points = 48;

double integrate(const std::function<double(double)>& f, std::span<const double> breaks,
                 double rel_tol) {
  QuadratureOptions options;
  options.rel_tol = rel_tol;
  options.abs_tol = 1e-300;
  return integrate_adaptive(f, breaks, options).value;
}

// Leaving the medium: incident from inside, relative index n_outside / n_medium = 1 / eta.
double transmittance(const GrosjeanBeam& m, double mu) {
  return fresnel_dielectric_transmittance(mu, 1.0 / m.eta);
}

double critical_cosine(const GrosjeanBeam& m) {
  return m.eta > 1.0 ? std::sqrt(1.0 - 1.0 / (m.eta * m.eta)) : 0.0;
}

// The multiply-scattered part of a first collision at z': the better dipole's source and image
// moved to z', with the strength the header derives, alpha' (1 - P(z')) per unit emission.
DipoleModel emission_dipole(const GrosjeanBeam& m, double depth) {
  DipoleModel dipole;
  dipole.strength = m.albedo * (1.0 - grosjean_beam_escape(m, depth));
  dipole.diffusion = m.diffusion;
  dipole.sigma_tr = m.sigma_tr;
  dipole.source_depth = depth;
  dipole.image_height = depth + 2.0 * m.boundary_height;
  dipole.fluence_weight = m.fluence_weight;
  dipole.flux_weight = m.flux_weight;
  return dipole;
}

// Power re-emitted per unit depth by first collisions at z', per unit power entering.
double emission_density(const GrosjeanBeam& m, double depth) {
  return m.sigma_t * m.albedo * std::exp(-m.sigma_t * depth);
}

// Breakpoints on [0, cutoff]: the integrand over z' has features of width ~`width` around
// `centre` (the point's depth, or the surface for reflectance), and decays on 1 / sigma_t'.
std::vector<double> depth_breaks(const GrosjeanBeam& m, double centre, double width) {
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

bool wants(ModelPart part, ModelPart piece) { return part == ModelPart::all || part == piece; }

}  // namespace

GrosjeanBeam grosjean_beam(const HalfSpaceMedium& medium) {
  medium.validate();
  GrosjeanBeam m;
  m.sigma_t = medium.reduced_sigma_t();
  m.albedo = medium.reduced_albedo();
  // Grosjean's D with reduced coefficients (point_source_grosjean.hpp; d'Eon 2012).
  m.diffusion = (2.0 * medium.sigma_a + medium.reduced_sigma_s()) / (3.0 * m.sigma_t * m.sigma_t);
  m.sigma_tr = std::sqrt(medium.sigma_a / m.diffusion);
  m.boundary_height = 2.0 * better_boundary_a(medium.eta) * m.diffusion;  // Bitterli §2.5
  m.fluence_weight = exitance_fluence_weight(medium.eta);
  m.flux_weight = exitance_flux_weight(medium.eta);
  m.eta = medium.eta;
  // P(z') = (1/2) int_{mu_c}^1 T(mu) e^{-x / mu} dmu by Gauss-Legendre in u, mu = mu_c +
  // (1 - mu_c) u^2: T goes as sqrt(mu - mu_c) above the critical cosine mu_c, smooth in u.
  // Against E_2(x) / 2 at eta = 1 it is within 1e-8 (tests; the worst near x = 1e-4, where
  // e^{-x / mu} turns over at mu ~ x, between the first nodes).
  const GaussLegendre rule = gauss_legendre(escape_points);
  const double mu_c = critical_cosine(m);
  std::vector<double> weights, rates;
  for (int k = 0; k < escape_points; ++k) {
    const double u = 0.5 * (1.0 + rule.nodes[static_cast<std::size_t>(k)]);
    const double mu = mu_c + (1.0 - mu_c) * u * u;
    const double jacobian = 0.5 * rule.weights[static_cast<std::size_t>(k)] * 2.0 * (1.0 - mu_c) * u;
    weights.push_back(0.5 * jacobian * transmittance(m, mu));
    rates.push_back(1.0 / mu);
  }
  m.escape = ExponentialSum(weights, rates);
  return m;
}

double grosjean_beam_escape(const GrosjeanBeam& m, double depth) {
  return m.escape(m.sigma_t * depth);
}

double grosjean_beam_reflectance(const GrosjeanBeam& m, double r, ModelPart part) {
  detail::check_radius(r);
  if (m.albedo == 0.0) return 0.0;
  if (r == 0.0 && wants(part, ModelPart::single)) return HUGE_VAL;  // ~ 1 / r (header)
  const auto integrand = [&](double depth) {
    double value = 0.0;
    if (wants(part, ModelPart::single)) {
      const double d = std::hypot(r, depth);
      value += depth * std::exp(-m.sigma_t * d) * transmittance(m, depth / d) * inv_four_pi /
               (d * d * d);
    }
    if (wants(part, ModelPart::multiple)) {
      value += dipole_reflectance(emission_dipole(m, depth), r);
    }
    return emission_density(m, depth) * value;
  };
  return integrate(integrand, depth_breaks(m, 0.0, r), 1e-9);
}

double grosjean_beam_total_reflectance(const GrosjeanBeam& m, ModelPart part) {
  if (m.albedo == 0.0) return 0.0;
  const auto integrand = [&](double depth) {
    double value = 0.0;
    if (wants(part, ModelPart::single)) value += grosjean_beam_escape(m, depth);
    if (wants(part, ModelPart::multiple)) {
      value += dipole_total_reflectance(emission_dipole(m, depth));
    }
    return emission_density(m, depth) * value;
  };
  return integrate(integrand, depth_breaks(m, 0.0, 1.0 / m.sigma_t), 1e-10);
}

// The once-scattered light through the annulus [r0, r1), per unit power entering. With the
// order of the header's double integral swapped: a path at cosine mu = cos theta from the
// normal reaches the annulus from depths z' in [r0, r1) cot theta, and over them
//   int alpha' s e^{-s z'} e^{-s z' / mu} dz' = alpha' mu / (1 + mu) [e^{-k z'}]_{z'_1}^{z'_0},
// k = s (1 + mu) / mu, leaving one integral over mu of (1/2) T(mu) times that.
double single_annulus(const GrosjeanBeam& m, double r0, double r1) {
  const double mu_critical = critical_cosine(m);
  const auto f = [&](double mu) {
    if (!(mu > 0.0)) return 0.0;
    const double cot = mu / std::sqrt(std::max(1.0 - mu * mu, 0.0));  // +inf at mu = 1
    const double k = m.sigma_t * (1.0 + mu) / mu;
    const double near = r0 == 0.0 ? 1.0 : std::exp(-k * r0 * cot);
    const double far = std::isfinite(r1 * cot) ? std::exp(-k * r1 * cot) : 0.0;
    return 0.5 * transmittance(m, mu) * m.albedo * mu / (1.0 + mu) * (near - far);
  };
  const std::vector<double> breaks{mu_critical, 1.0};
  return integrate(f, breaks, 1e-10);
}

std::vector<double> grosjean_beam_reflectance_annulus_average(const GrosjeanBeam& m,
                                                              std::span<const double> r_edges,
                                                              ModelPart part) {
  detail::check_edges(r_edges, "r_edges");
  std::vector<double> average(r_edges.size() - 1, 0.0);
  if (m.albedo == 0.0) return average;
  for (std::size_t i = 0; i + 1 < r_edges.size(); ++i) {
    const double r0 = r_edges[i], r1 = r_edges[i + 1];
    double integral = wants(part, ModelPart::single) ? single_annulus(m, r0, r1) : 0.0;
    if (wants(part, ModelPart::multiple)) {
      const auto multiple = [&](double depth) {
        return emission_density(m, depth) *
               dipole_reflectance_annulus_integral(emission_dipole(m, depth), r0, r1);
      };
      integral += integrate(multiple, depth_breaks(m, 0.0, r1), 1e-9);
    }
    average[i] = integral / (pi * (r1 * r1 - r0 * r0));
  }
  return average;
}

double grosjean_beam_fluence(const GrosjeanBeam& m, double r, double z) {
  detail::check_radius(r);
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
  return integrate(integrand, depth_breaks(m, z, r), 1e-9);
}

std::vector<double> grosjean_beam_fluence_cell_average(const GrosjeanBeam& m,
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
      // The unscattered beam: int exp(-s z) dz over the cell, on the axis.
      if (r0 == 0.0) integral += std::exp(-s * z0) * -std::expm1(-s * (z1 - z0)) / s;
      average[i * nz + j] = integral / (pi * (r1 * r1 - r0 * r0) * (z1 - z0));
    }
  }
  return average;
}

}  // namespace scatterlab
