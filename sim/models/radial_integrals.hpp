#pragma once
// Closed-form integrals of the point-source kernels over annuli and shells, shared by the
// diffusion models (private to sim/models). Distances d = sqrt(r^2 + h^2) from a point at height
// h off the plane; r dr = d dd turns every annulus integral into a one-dimensional one in d.

#include <cmath>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "scatterlab/core/error.hpp"

namespace scatterlab::detail {

// int_d0^d1 exp(-s d) dd = exp(-s d0) (1 - exp(-s (d1 - d0))) / s, and d1 - d0 at s = 0.
inline double exp_integral_linear(double s, double d0, double d1) {
  const double width = d1 - d0;
  if (s * width < 1e-300) return std::exp(-s * d0) * width;
  return std::exp(-s * d0) * -std::expm1(-s * width) / s;
}

// E_1(x) = int_1^inf exp(-x t) / t dt for x > 0 (Abramowitz & Stegun 5.1.1), through
// std::expint, which is Ei: E_1(x) = -Ei(-x). +infinity at x = 0, 0 for huge x.
inline double exponential_integral_e1(double x) {
  if (x <= 0.0) return HUGE_VAL;
  if (x > 700.0) return 0.0;
  return -std::expint(-x);
}

// int_d0^d1 exp(-s d) / d dd = E_1(s d0) - E_1(s d1) (s > 0, 0 < d0 <= d1).
inline double exp_over_d_integral(double s, double d0, double d1) {
  return exponential_integral_e1(s * d0) - exponential_integral_e1(s * d1);
}

// A radius where a profile is evaluated: finite and >= 0 (InputError "r" otherwise).
inline void check_radius(double r) {
  if (!(r >= 0.0) || !std::isfinite(r)) {
    throw InputError("r", "got " + std::to_string(r), "a finite number >= 0");
  }
}

// Edges must be finite, >= 0, increasing, at least two.
inline void check_edges(std::span<const double> edges, const std::string& field) {
  if (edges.size() < 2) throw InputError(field, "fewer than two edges", "at least two edges");
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (!(edges[i] >= 0.0) || !std::isfinite(edges[i]) || (i > 0 && !(edges[i] > edges[i - 1]))) {
      throw InputError(field, "edge " + std::to_string(i) + " is " + std::to_string(edges[i]),
                       "finite edges >= 0 in increasing order");
    }
  }
}

// Averages over the annuli between consecutive edges, integral(r0, r1) / (pi (r1^2 - r0^2)), from
// a model's integral of R 2 pi r dr over [r0, r1); the edges are checked (field "r_edges").
template <class AnnulusIntegral>
std::vector<double> annulus_averages(std::span<const double> r_edges, AnnulusIntegral integral) {
  check_edges(r_edges, "r_edges");
  std::vector<double> average(r_edges.size() - 1);
  for (std::size_t i = 0; i + 1 < r_edges.size(); ++i) {
    const double r0 = r_edges[i], r1 = r_edges[i + 1];
    average[i] = integral(r0, r1) / (std::numbers::pi * (r1 * r1 - r0 * r0));
  }
  return average;
}

}  // namespace scatterlab::detail
