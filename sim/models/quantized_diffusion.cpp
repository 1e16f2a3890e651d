#include "scatterlab/models/quantized_diffusion.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <string>

#include "erfcx.hpp"
#include "radial_integrals.hpp"
#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/quadrature.hpp"
#include "scatterlab/models/boundary_reflection.hpp"

namespace scatterlab {
namespace {

constexpr double sqrt_pi = 1.0 / std::numbers::inv_sqrtpi;
constexpr double sqrt_two_pi = std::numbers::sqrt2 * sqrt_pi;

// The time grid (header, "Time grid"), in the dimensionless time tau = sigma_t'^2 D t (D t is a
// squared length; the grid's lengths scale with the extended source's depth 1 / sigma_t').
//
// Step h = ln q of the midpoint rule in u = ln t: its error falls as C exp(-pi^2 / h) (header).
// Measured C (tests/unit/test_quantized_diffusion.cpp): ~100 for most annuli. h = pi^2 /
// ln(kSpectralMargin / eps) keeps that part ~40 times below eps or more: q = 1.85, 1.61, 1.48 at
// eps = 1e-2, 1e-4, 1e-6.
//
// Far from the beam in an absorbing medium the integrand is a narrow peak in u: at distance r,
// F ~ exp(-r^2 / (4 D t) - sigma_a t) peaks where the two terms are equal, and there its second
// derivative in u is -r sigma_tr (sigma_tr = sqrt(sigma_a / D)), so F is a Gaussian of variance
// 1 / (r sigma_tr) in u, whose peak value exp(-r sigma_tr) is small against F elsewhere in the
// strip. The rule's relative error on such a Gaussian is ~ 2 exp(-2 pi^2 / (h^2 r sigma_tr)) (the
// same bound on the strip of half-width 2 pi / (h r sigma_tr), where it is least), which the step
// above left at 13 eps on the ring [9.9, 10] / sigma_t' at albedo 0.01 (r sigma_tr = 17). So h is
// also at most pi sqrt(2 / (X ln(kPeakMargin / eps))) with X = r_max sigma_tr: 0.01-0.03 eps on
// every ring out to r_max, for a few more Gaussians (up to 135 at eps = 1e-4, from 121).
constexpr double kSpectralMargin = 1e5;
constexpr double kPeakMargin = 1e3;
// The smallest annulus edge the accuracy is stated for, r_min = 1e-3 / sigma_t'. Below the
// first node the rule is cut: [0, t_1') is one Gaussian (exact for the t^(-1/2) flux term, see
// below), and the cut costs the midpoint rule an end correction h^2 / 24 F'(u_1') ~ h^2 / 48 F
// there, with F = t f ~ sqrt(t) for the inner annuli (and the total): relative to the annulus
// [0, r_min), whose integral is ~ 2 F at D t ~ r_min^2, that is (h^2 / 96) sqrt(t_1 / t(r_min))
// < 0.01 tolerance with tau_1 = (1e-3 tolerance)^2. Each decade of tau costs ln(10) / h ~ 4
// Gaussians.
constexpr double kMinRadius = 1e-3;  // r_min sigma_t'
// The sum stops once the Gaussians reach past the largest annulus the accuracy is stated for,
// r_max = 10 / sigma_t' (v >= 100 (r_max + 1 / sigma_t' + d_e)^2), and the rest of the total
// reflectance is below relative_tolerance / 8 of it (remainder bound below).
constexpr double kMaxRadius = 10.0;  // r_max sigma_t'
constexpr std::size_t kMaxGaussians = 1'000'000;

// The depth factors of one Gaussian of variance v (header): s = sigma_t', d >= 0.
// J(v, d) = (s / 2) exp(-d^2 / 2v) erfcx((d + s v) / sqrt(2v)), the argument >= 0.
double j_term(double s, double v, double d) {
  const double root = std::sqrt(2.0 * v);
  const double a = d / root;
  return 0.5 * s * std::exp(-a * a) * detail::erfcx(a + s * v / root);
}

// g1(v, d) - J(v, d) without the cancellation: with a = d / sqrt(2v), x = a + s v / sqrt(2v),
// J / g1 = s sqrt(pi v / 2) erfcx(x) = sqrt(pi) (x - a) erfcx(x), so
// g1 - J = g1 [ (1 - sqrt(pi) x erfcx(x)) + sqrt(pi) a erfcx(x) ], two terms >= 0.
double flux_term(double s, double v, double d) {
  const double root = std::sqrt(2.0 * v);
  const double a = d / root, x = a + s * v / root;
  return std::exp(-a * a) / (sqrt_two_pi * std::sqrt(v)) *
         (detail::erfcx_complement(x) + sqrt_pi * a * detail::erfcx(x));
}

// K(v, z) = (s / 2) exp(-s z + s^2 v / 2) erfc(y), y = (s v - z) / sqrt(2v) (header). Since
// y^2 = s^2 v / 2 - s z + z^2 / 2v, the exponent is y^2 - z^2 / 2v and
// K = (s / 2) exp(-z^2 / 2v) erfcx(y), the stable form for y >= 0 (erfcx(y) <= 1). For y < 0,
// i.e. z > s v, erfcx(y) ~ 2 exp(y^2) could overflow, but there the original form is safe:
// its exponent -s (z - s v / 2) < -s^2 v / 2 < 0 and erfc(y) lies in (1, 2].
double k_term(double s, double v, double z) {
  const double root = std::sqrt(2.0 * v);
  const double y = (s * v - z) / root;
  if (y >= 0.0) {
    const double a = z / root;
    return 0.5 * s * std::exp(-a * a) * detail::erfcx(y);
  }
  return 0.5 * s * std::exp(-s * (z - 0.5 * s * v)) * std::erfc(y);
}

// R_d's depth factor per unit strength, C_phi phi(0) + C_E D dphi/dz(0) of one Gaussian with
// g2 and the weight taken out (header: the surface values).
double surface_term(const QuantizedDiffusion& m, double v) {
  const double s = m.sigma_t, de = m.image_offset;
  const double fluence = j_term(s, v, 0.0) - j_term(s, v, de);
  const double flux = m.diffusion * s * (flux_term(s, v, 0.0) + flux_term(s, v, de));
  return m.fluence_weight * fluence + m.flux_weight * flux;
}

// The continuum total per unit strength: dipole_total_reflectance of a unit source at z'
// (models/dipole.hpp) integrated against s exp(-s z') dz', with int s e^{-s z'} e^{-sigma_tr z'}
// dz' = s / (s + sigma_tr):
//   s / (s + sigma_tr) [C_E (1 + e) / 2 + C_phi (1 - e) / (2 D sigma_tr)], e = exp(-sigma_tr d_e),
// and (1 - e) / sigma_tr -> d_e at sigma_tr = 0.
double continuum_total(const QuantizedDiffusion& m, double sigma_tr) {
  const double s = m.sigma_t, de = m.image_offset;
  const double e = std::exp(-sigma_tr * de);
  const double one_minus_e_over_s =
      sigma_tr * de < 1e-300 ? de : -std::expm1(-sigma_tr * de) / sigma_tr;
  return s / (s + sigma_tr) *
         (m.flux_weight * 0.5 * (1.0 + e) +
          m.fluence_weight * one_minus_e_over_s / (2.0 * m.diffusion));
}

// exp(-r0^2 / 2v) - exp(-r1^2 / 2v), the integral of g2(v, r) 2 pi r dr over [r0, r1), as
// exp(-r0^2 / 2v) (1 - exp(-(r1 - r0)(r1 + r0) / 2v)) so that thin and inner annuli keep their
// digits.
double annulus_mass(double v, double r0, double r1) {
  return std::exp(-r0 * r0 / (2.0 * v)) * -std::expm1(-(r1 - r0) * (r1 + r0) / (2.0 * v));
}

// The depth integrand of the fluence: K(v, z) - J(v, z + d_e) (>= 0: the image Gaussian is
// never nearer than the source).
struct FluenceDepth {
  double s, v, de;
  double operator()(double z) const { return k_term(s, v, z) - j_term(s, v, z + de); }
};

}  // namespace

QuantizedDiffusion quantized_diffusion(const HalfSpaceMedium& medium, double relative_tolerance) {
  medium.validate();
  if (!(relative_tolerance >= 1e-6 && relative_tolerance <= 1e-2)) {
    throw InputError("relative_tolerance", "got " + std::to_string(relative_tolerance),
                     "a number in [1e-6, 1e-2]");
  }
  QuantizedDiffusion m;
  const double s = medium.reduced_sigma_t();
  const double albedo = medium.reduced_albedo();
  m.strength = albedo * albedo;  // Grosjean: alpha'^2 (header)
  m.sigma_t = s;
  m.diffusion = (2.0 * medium.sigma_a + medium.reduced_sigma_s()) / (3.0 * s * s);  // Grosjean D
  m.image_offset = 4.0 * better_boundary_a(medium.eta) * m.diffusion;  // d_e = 2 z_b = 4 A D
  m.fluence_weight = exitance_fluence_weight(medium.eta);
  m.flux_weight = exitance_flux_weight(medium.eta);

  const double sigma_a = medium.sigma_a, d = m.diffusion;
  const double time_unit = 1.0 / (s * s * d);  // t = time_unit * tau
  const double peak = kMaxRadius / s * std::sqrt(sigma_a / d);  // r_max sigma_tr
  const double h =
      std::min(pi * pi / std::log(kSpectralMargin / relative_tolerance),
               pi * std::sqrt(2.0 / (peak * std::log(kPeakMargin / relative_tolerance))));
  const double ratio = std::exp(h);  // q
  const double tau_1 = (kMinRadius * relative_tolerance) * (kMinRadius * relative_tolerance);
  const double reach = (kMaxRadius + 1.0) / s + m.image_offset;
  const double v_reach = 100.0 * reach * reach;
  const double remainder_allowed =
      relative_tolerance / 8.0 * continuum_total(m, std::sqrt(sigma_a / d));
  // Node i >= 1 of the rule in u = ln t sits at the logarithmic mean t_i* = (t_i+1 - t_i) / h
  // of its interval, so that its weight at sigma_a = 0 is the interval's length:
  // (t_i+1 - t_i) f(t_i*) = h t_i* f(t_i*). Its cell in u is [ln t_i* - h/2, ln t_i* + h/2), which
  // starts at t_1' = t_1 (q - 1) / (h sqrt(q)), a little above t_1: the first Gaussian covers
  // [0, t_1') so that the cells tile the time axis.
  const double t_1 = time_unit * tau_1;
  const double first_end = t_1 * (ratio - 1.0) / (h * std::sqrt(ratio));
  // First interval [0, t_1'): there the flux term behaves as t^(-1/2) (g1(v, 0) = 1 /
  // sqrt(4 pi D t)) and the midpoint t_1' / 2 would give only 1 / sqrt(2) of its integral; the
  // Gaussian sits at t_1' / 4 (v_0 = D t_1' / 2), where t_1' (t_1' / 4)^(-1/2) = 2 sqrt(t_1') is
  // exact, leaving O(t_1'^(3/2)).
  m.variance.push_back(0.5 * d * first_end);
  m.weight.push_back(detail::exp_integral_linear(sigma_a, 0.0, first_end));
  for (double t_prev = t_1;; t_prev *= ratio) {
    const double t = t_prev * ratio;
    const double t_node = (t - t_prev) / h;  // logarithmic mean of [t_prev, t)
    const double v = 2.0 * d * t_node;       // the 3-D Gaussian's variance per axis, 2 D t
    m.variance.push_back(v);
    m.weight.push_back((t - t_prev) * std::exp(-sigma_a * t_node));
    if (m.variance.size() >= kMaxGaussians) {
      throw std::logic_error("quantized_diffusion: the time grid did not end");
    }
    if (v < v_reach) continue;
    // Remainder of the total beyond t: its integrand F(t) = exp(-sigma_a t) surface_term(2 D t)
    // falls as t^(-3/2) once v >> (1 / s + d_e)^2 (the pair of Gaussians looks like a surface
    // dipole), so int_t^inf F <= F(t) min(2 t, 1 / sigma_a); F at the node bounds F(t).
    const double f = std::exp(-sigma_a * t_node) * surface_term(m, v);
    const double span = sigma_a > 0.0 ? std::min(2.0 * t, 1.0 / sigma_a) : 2.0 * t;
    if (f * span <= remainder_allowed) break;
  }
  return m;
}

double quantized_diffusion_reflectance(const QuantizedDiffusion& m, double r) {
  detail::check_radius(r);
  if (m.strength == 0.0) return 0.0;
  if (r == 0.0) return HUGE_VAL;  // the continuum's R_d ~ 1 / r (header)
  double sum = 0.0;
  for (std::size_t i = 0; i < m.variance.size(); ++i) {
    const double v = m.variance[i];
    const double g2 = std::exp(-r * r / (2.0 * v)) / (2.0 * pi * v);
    sum += m.weight[i] * g2 * surface_term(m, v);
  }
  return m.strength * sum;
}

double quantized_diffusion_total_reflectance(const QuantizedDiffusion& m) {
  if (m.strength == 0.0) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < m.variance.size(); ++i) {
    sum += m.weight[i] * surface_term(m, m.variance[i]);
  }
  return m.strength * sum;
}

std::vector<double> quantized_diffusion_reflectance_annulus_average(
    const QuantizedDiffusion& m, std::span<const double> r_edges) {
  detail::check_edges(r_edges, "r_edges");
  const std::size_t n = r_edges.size() - 1;
  std::vector<double> average(n, 0.0);
  if (m.strength == 0.0) return average;
  for (std::size_t i = 0; i < m.variance.size(); ++i) {
    const double v = m.variance[i];
    const double depth = m.weight[i] * surface_term(m, v);
    for (std::size_t k = 0; k < n; ++k) {
      average[k] += depth * annulus_mass(v, r_edges[k], r_edges[k + 1]);
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    const double r0 = r_edges[k], r1 = r_edges[k + 1];
    average[k] *= m.strength / (pi * (r1 - r0) * (r1 + r0));
  }
  return average;
}

std::vector<double> quantized_diffusion_fluence_cell_average(const QuantizedDiffusion& m,
                                                             std::span<const double> r_edges,
                                                             std::span<const double> z_edges) {
  detail::check_edges(r_edges, "r_edges");
  detail::check_edges(z_edges, "z_edges");
  const std::size_t nr = r_edges.size() - 1, nz = z_edges.size() - 1;
  std::vector<double> average(nr * nz, 0.0);
  if (m.strength == 0.0) return average;
  std::vector<double> depth(nz);  // one Gaussian's z integrals, reused
  QuadratureOptions options;
  options.rel_tol = 1e-9;  // far below the smallest relative_tolerance, 1e-6
  for (std::size_t i = 0; i < m.variance.size(); ++i) {
    const double v = m.variance[i];
    const FluenceDepth integrand{m.sigma_t, v, m.image_offset};
    const std::function<double(double)> f = [&integrand](double z) { return integrand(z); };
    // K rises from s/2 to s within a few sqrt(v) of the surface, then decays on 1 / sigma_t':
    // breakpoints there start the subdivision where the integrand has its features.
    const double w = std::sqrt(v), l = 1.0 / m.sigma_t;
    const std::array<double, 5> features{w, 4.0 * w, 16.0 * w, l, 4.0 * l};
    for (std::size_t j = 0; j < nz; ++j) {
      const double z0 = z_edges[j], z1 = z_edges[j + 1];
      std::array<double, 7> breaks{};
      std::size_t count = 0;
      breaks[count++] = z0;
      for (const double b : features) {
        if (!(b > z0 && b < z1)) continue;
        std::size_t k = count++;  // insertion keeps breaks[0, count) increasing
        for (; breaks[k - 1] > b; --k) breaks[k] = breaks[k - 1];
        breaks[k] = b;
      }
      breaks[count++] = z1;
      // K - J cancels for v >> (z + d_e)^2 (both ~ 1 / sqrt(2 pi v)), leaving rounding noise of
      // ~eps K that no subdivision removes: the absolute tolerance is 1e-10 of the scale of K
      // over the cell, far below anything these Gaussians add to a cell average.
      const double k_scale = k_term(integrand.s, v, z0) + k_term(integrand.s, v, 0.5 * (z0 + z1)) +
                             k_term(integrand.s, v, z1);
      options.abs_tol = std::max(1e-300, 1e-10 * k_scale * (z1 - z0));
      depth[j] =
          integrate_adaptive(f, std::span<const double>(breaks.data(), count), options).value;
    }
    for (std::size_t k = 0; k < nr; ++k) {
      const double radial = m.weight[i] * annulus_mass(v, r_edges[k], r_edges[k + 1]);
      for (std::size_t j = 0; j < nz; ++j) average[k * nz + j] += radial * depth[j];
    }
  }
  for (std::size_t k = 0; k < nr; ++k) {
    const double r0 = r_edges[k], r1 = r_edges[k + 1];
    for (std::size_t j = 0; j < nz; ++j) {
      average[k * nz + j] *=
          m.strength / (pi * (r1 - r0) * (r1 + r0) * (z_edges[j + 1] - z_edges[j]));
    }
  }
  return average;
}

QuantizedDiffusionContinuum::QuantizedDiffusionContinuum(const HalfSpaceMedium& medium)
    : s_(medium.reduced_sigma_t()),
      strength_(medium.reduced_albedo() * medium.reduced_albedo()),
      cutoff_(50.0 / s_),            // exp(-50) = 2e-22 of the sources lie deeper
      base_(better_dipole(medium)),  // Grosjean's D and the better dipole's boundary
      image_offset_(base_.image_height - base_.source_depth) {}  // 4 A D

DipoleModel QuantizedDiffusionContinuum::at(double depth) const {
  DipoleModel d = base_;
  d.strength = 1.0;
  d.source_depth = depth;
  d.image_height = depth + image_offset_;
  return d;
}

template <class F>
double QuantizedDiffusionContinuum::depth_integral(F f, std::vector<double> breaks) const {
  for (const double b : {0.0, cutoff_, 1.0 / s_, 5.0 / s_}) breaks.push_back(b);
  std::erase_if(breaks, [this](double b) { return !(b >= 0.0 && b <= cutoff_); });
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  QuadratureOptions options;
  options.rel_tol = 1e-10;  // 1e-4 of the smallest relative_tolerance the sum accepts
  options.abs_tol = 1e-300;
  const auto g = [&](double z) { return strength_ * s_ * std::exp(-s_ * z) * f(z); };
  return integrate_adaptive(g, breaks, options).value;
}

double QuantizedDiffusionContinuum::total() const {
  return depth_integral([&](double z) { return dipole_total_reflectance(at(z)); }, {});
}

double QuantizedDiffusionContinuum::annulus_average(double r0, double r1) const {
  const double integral =
      depth_integral([&](double z) { return dipole_reflectance_annulus_integral(at(z), r0, r1); },
                     {0.25 * r0, r0, 4.0 * r0, r1});
  return integral / (pi * (r1 * r1 - r0 * r0));
}

double QuantizedDiffusionContinuum::fluence_cell_average(double r0, double r1, double z0,
                                                         double z1) const {
  const std::vector<double> re{r0, r1}, ze{z0, z1};
  return depth_integral([&](double z) { return dipole_fluence_cell_average(at(z), re, ze)[0]; },
                        {z0, z1, 0.5 * (z0 + z1), z1 + r1});
}

}  // namespace scatterlab
