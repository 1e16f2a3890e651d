#pragma once
// Globally adaptive Gauss-Kronrod quadrature for smooth one-dimensional integrands on finite
// intervals: the 10-point Gauss / 21-point Kronrod pair with QUADPACK's error estimate
// (Piessens, de Doncker-Kapenga, Ueberhuber & Kahaner 1983, "QUADPACK", routines QK21 and QAG).
// Used by the exact transport solutions (models/) and by tests as an independent integrator.

#include <functional>
#include <span>
#include <vector>

namespace scatterlab {

struct QuadratureOptions {
  double abs_tol = 0.0;  // stop once the error estimate is <= max(abs_tol, rel_tol * |value|)
  double rel_tol = 1e-12;
  int max_intervals = 1000;  // subintervals kept at most; the largest-error one is bisected
};

struct QuadratureResult {
  double value = 0.0;
  double error = 0.0;      // QUADPACK-style estimate of |value - exact|
  double abs_value = 0.0;  // estimate of the integral of |f|, the scale that rounding acts on
  int evaluations = 0;     // calls of the integrand (21 per subinterval)
  int intervals = 0;
  bool converged = false;  // error <= the requested tolerance
  // Not converged only because every subinterval's error sits at the rounding floor (50 eps
  // times the integral of |f| there): the value is then as good as double precision allows.
  bool rounding_limited = false;
};

// Integral of f over [breakpoints.front(), breakpoints.back()]; the breakpoints (at least two,
// finite and non-decreasing) start the subdivision, so put them where f has kinks or sharp
// features. Throws InputError ("breakpoints") when they are not usable.
QuadratureResult integrate_adaptive(const std::function<double(double)>& f,
                                    std::span<const double> breakpoints,
                                    const QuadratureOptions& options = {});

// Integral of f over [a, b] (finite, a <= b).
QuadratureResult integrate_adaptive(const std::function<double(double)>& f, double a, double b,
                                    const QuadratureOptions& options = {});

// The n-point Gauss-Legendre rule on [-1, 1] (exact for polynomials of degree 2n - 1), for
// smooth integrands whose cost must be fixed in advance.
struct GaussLegendre {
  std::vector<double> nodes;    // on [-1, 1]
  std::vector<double> weights;  // sum to 2
};
GaussLegendre gauss_legendre(int n);

}  // namespace scatterlab
