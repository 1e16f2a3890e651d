#include "scatterlab/models/lit_sphere_exitance.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/frame.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/quadrature.hpp"
#include "scatterlab/core/random.hpp"
#include "scatterlab/models/bssrdf.hpp"

namespace scatterlab {

LitSphereExitance lit_sphere_exitance(const DiffusionProfile& profile, double radius,
                                      std::span<const double> psi_edges, int samples,
                                      std::uint64_t seed) {
  if (!(radius > 0.0) || !std::isfinite(radius))
    throw InputError("radius", "must be finite and > 0", "a radius > 0");
  if (samples < 2) throw InputError("samples", "too few samples per bin", "at least 2");
  if (psi_edges.size() < 2) throw InputError("psi", "needs at least two edges", "edges in [0, pi]");
  for (std::size_t i = 0; i < psi_edges.size(); ++i) {
    const bool inside = psi_edges[i] >= 0.0 && psi_edges[i] <= std::numbers::pi;
    if (!inside || (i > 0 && !(psi_edges[i] > psi_edges[i - 1])))
      throw InputError("psi", "edge " + std::to_string(i) + " is out of order or range",
                       "increasing edges in [0, pi]");
  }

  const double eta = profile.medium().eta;
  check_bssrdf_eta(eta, "eta");
  const RadialProfileSampler sampler(profile, 2.0 * radius);
  // E_0 = 1 / (pi R^2): unit power meets the sphere. The exit factor integrates eq. 2.16's
  // F_t(w_o) / (pi 4 C_phi) over the outgoing hemisphere.
  const double scale = exit_transmittance_ratio(eta) / (std::numbers::pi * radius * radius);

  const std::size_t bins = psi_edges.size() - 1;
  LitSphereExitance result;
  result.mean.resize(bins);
  result.stderr_of_mean.resize(bins);
  // A measured profile's own noise: the integral is linear in the rings' means, M = sum_k W_k
  // R_k, so its variance from them is sum_k (W_k sigma_k)^2, W_k estimated with the same samples.
  const RingProfile* rings = profile.rings();
  std::vector<double> ring_weight(rings != nullptr ? rings->mean.size() : 0);
  for (std::size_t b = 0; b < bins; ++b) {
    PhotonRandom random(seed, b);
    std::fill(ring_weight.begin(), ring_weight.end(), 0.0);
    const double cos_hi = std::cos(psi_edges[b]), cos_lo = std::cos(psi_edges[b + 1]);
    double sum = 0.0, sum_sq = 0.0;
    for (int s = 0; s < samples; ++s) {
      const auto u = random.next4();
      const auto v = random.next4();
      // x_o uniform over the bin's area (uniform in cos psi); the lit pole is (0, 0, -R), and by
      // the symmetry about z one azimuth (x > 0) stands for all.
      const double cos_psi = cos_lo + u[0] * (cos_hi - cos_lo);
      const double sin_psi = std::sqrt(std::max(0.0, 1.0 - cos_psi * cos_psi));
      const Vec3 x_o = radius * Vec3(sin_psi, 0.0, -cos_psi);

      // Along the profile: a chord d and an azimuth about x_o; cos gamma = 1 - d^2 / (2 R^2).
      double density = 0.0;
      const double d = sampler.sample(u[1], density);
      const double cos_gamma = std::clamp(1.0 - d * d / (2.0 * radius * radius), -1.0, 1.0);
      const double sin_gamma = std::sqrt(std::max(0.0, 1.0 - cos_gamma * cos_gamma));
      const double beta = 2.0 * std::numbers::pi * u[2];
      const Vec3 from_profile =
          radius * Frame(x_o / radius)
                       .to_world(sin_gamma * std::cos(beta), sin_gamma * std::sin(beta), cos_gamma);
      // Along the light: a point of the shadow disc, lifted onto the lit hemisphere (z < 0).
      const double rho = radius * std::sqrt(v[0]), phi = 2.0 * std::numbers::pi * v[1];
      const double x = rho * std::cos(phi), y = rho * std::sin(phi);
      const Vec3 from_light(x, y, -std::sqrt(std::max(0.0, radius * radius - x * x - y * y)));

      double value = 0.0;
      for (const Vec3& x_i : {from_profile, from_light}) {
        // Lit where the outward normal faces the light (travelling along +z): cos = -n_z.
        const double cos_in = -x_i.z() / radius;
        if (!(cos_in > 0.0)) continue;
        const double chord = (x_i - x_o).norm();
        const double p_profile =
            chord > 0.0 ? sampler.density(chord) / (2.0 * std::numbers::pi * chord) : 0.0;
        const double p_light = cos_in / (std::numbers::pi * radius * radius);
        const double weight =
            cos_in * fresnel_dielectric_transmittance(cos_in, eta) / (p_profile + p_light);
        value += weight * profile.reflectance(chord);
        if (rings != nullptr) {
          const int ring = rings->ring_of(chord);
          if (ring >= 0) ring_weight[ring] += weight / samples;
        }
      }
      sum += value;
      sum_sq += value * value;
    }
    const double n = samples;
    const double mean = sum / n;
    const double variance = std::max(0.0, (sum_sq - n * mean * mean) / (n - 1.0));
    double profile_variance = 0.0;
    for (std::size_t k = 0; k < ring_weight.size(); ++k)
      profile_variance += std::pow(ring_weight[k] * rings->stderr_of_mean[k], 2);
    result.mean[b] = scale * mean;
    result.stderr_of_mean[b] = scale * std::sqrt(variance / n + profile_variance);
  }
  return result;
}

double lit_sphere_exitance_quadrature(const DiffusionProfile& profile, double radius, double psi_lo,
                                      double psi_hi, int nodes) {
  const double eta = profile.medium().eta;
  check_bssrdf_eta(eta, "eta");
  const GaussLegendre rule = gauss_legendre(nodes);
  const double c_lo = std::cos(psi_hi), c_hi = std::cos(psi_lo);
  const QuadratureOptions tight{0.0, 1e-8, 2000};
  double average = 0.0;
  for (std::size_t k = 0; k < rule.nodes.size(); ++k) {
    const double cos_o = c_lo + 0.5 * (c_hi - c_lo) * (rule.nodes[k] + 1.0);
    const double sin_o = std::sqrt(1.0 - cos_o * cos_o);
    const double psi_o = std::acos(cos_o);
    const auto over_psi_i = [&](double psi_i) {
      const double ci = std::cos(psi_i), si = std::sin(psi_i);
      const auto over_phi = [&](double phi) {
        const double cos_gamma = si * sin_o * std::cos(phi) + ci * cos_o;
        const double chord = radius * std::sqrt(std::max(0.0, 2.0 * (1.0 - cos_gamma)));
        return profile.reflectance(chord);
      };
      // Symmetric in phi: twice [0, pi]; the peak (x_i = x_o) sits at phi = 0.
      const double ring = 2.0 * integrate_adaptive(over_phi, 0.0, pi, tight).value;
      return radius * radius * si * ci * fresnel_dielectric_transmittance(ci, eta) * ring;
    };
    std::vector<double> breaks{0.0, pi / 2.0};
    if (psi_o < pi / 2.0) breaks.insert(breaks.begin() + 1, psi_o);
    const double m = integrate_adaptive(over_psi_i, breaks, tight).value;
    average += 0.5 * rule.weights[k] * m;  // weights sum to 2 on [-1, 1]
  }
  return exit_transmittance_ratio(eta) * average / (pi * radius * radius);
}

}  // namespace scatterlab
