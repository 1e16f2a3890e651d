#include "scatterlab/core/quadrature.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>
#include <string>
#include <vector>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"

namespace scatterlab {
namespace {

// QUADPACK QK21 abscissae and weights (Piessens et al. 1983, QK21): xgk[1], xgk[3], ..., xgk[9]
// are the 10-point Gauss-Legendre nodes, the others the Kronrod extension; xgk[10] = 0 is the
// centre. The Gauss rule is exact to degree 19, the Kronrod rule to degree 31 (tested).
constexpr std::array<double, 11> xgk = {
    0.995657163025808080735527280689003, 0.973906528517171720077964012084452,
    0.930157491355708226001207180059508, 0.865063366688984510732096688423493,
    0.780817726586416897063717578345042, 0.679409568299024406234327365114874,
    0.562757134668604683339000099272694, 0.433395394129247190799265943165784,
    0.294392862701460198131126603103866, 0.148874338981631210884826001129720,
    0.000000000000000000000000000000000};
constexpr std::array<double, 11> wgk = {
    0.011694638867371874278064396062192, 0.032558162307964727478818972459390,
    0.054755896574351996031381300244580, 0.075039674810919952767043140916190,
    0.093125454583697605535065465083366, 0.109387158802297641899210590325805,
    0.123491976262065851077208745813015, 0.134709217311473325928054001771707,
    0.142775938577060080797094273138717, 0.147739104901338491374841515972068,
    0.149445554002916905664936468389821};
constexpr std::array<double, 5> wg = {
    0.066671344308688137593568809893332, 0.149451349150580593145776339657697,
    0.219086362515982043995534934228163, 0.269266719309996355091226921569469,
    0.295524224714752870173892994651338};

struct Interval {
  double a = 0.0;
  double b = 0.0;
  double value = 0.0;
  double error = 0.0;
  double abs_value = 0.0;
  bool improvable = true;  // false once the error is at the rounding floor or b - a is minimal
};

// One 21-point Kronrod estimate with QUADPACK's error heuristic (QK21): the raw |K - G| is
// rescaled by the spread resasc as resasc * min(1, (200 |K - G| / resasc)^1.5), and never
// taken below 50 eps times the integral of |f| (the rounding floor).
Interval kronrod21(const std::function<double(double)>& f, double a, double b) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const double centre = 0.5 * (a + b);
  const double half = 0.5 * (b - a);
  std::array<double, 10> left{};
  std::array<double, 10> right{};
  const double f_centre = f(centre);
  double gauss = 0.0;
  double kronrod = wgk[10] * f_centre;
  double abs_sum = std::abs(kronrod);
  for (std::size_t j = 0; j < 10; ++j) {
    const double offset = half * xgk[j];
    left[j] = f(centre - offset);
    right[j] = f(centre + offset);
    const double sum = left[j] + right[j];
    kronrod += wgk[j] * sum;
    abs_sum += wgk[j] * (std::abs(left[j]) + std::abs(right[j]));
    if (j % 2 == 1) gauss += wg[j / 2] * sum;
  }
  const double mean = 0.5 * kronrod;
  double spread = wgk[10] * std::abs(f_centre - mean);
  for (std::size_t j = 0; j < 10; ++j) {
    spread += wgk[j] * (std::abs(left[j] - mean) + std::abs(right[j] - mean));
  }
  Interval out;
  out.a = a;
  out.b = b;
  out.value = kronrod * half;
  out.abs_value = abs_sum * std::abs(half);
  spread *= std::abs(half);
  double error = std::abs((kronrod - gauss) * half);
  if (spread != 0.0 && error != 0.0) {
    error = spread * std::min(1.0, std::pow(200.0 * error / spread, 1.5));
  }
  const double floor = 50.0 * eps * out.abs_value;
  if (error <= floor) {
    error = floor;
    out.improvable = false;
  }
  out.error = error;
  const double width_floor = 8.0 * eps * std::max(std::abs(a), std::abs(b));
  if (b - a <= width_floor) out.improvable = false;
  return out;
}

}  // namespace

QuadratureResult integrate_adaptive(const std::function<double(double)>& f,
                                    std::span<const double> breakpoints,
                                    const QuadratureOptions& options) {
  if (breakpoints.size() < 2) {
    throw InputError("breakpoints", "got " + std::to_string(breakpoints.size()) + " points",
                     "at least two finite, non-decreasing points");
  }
  for (std::size_t i = 0; i < breakpoints.size(); ++i) {
    if (!std::isfinite(breakpoints[i]) || (i > 0 && breakpoints[i] < breakpoints[i - 1])) {
      throw InputError("breakpoints", "point " + std::to_string(i) + " is not finite or decreases",
                       "at least two finite, non-decreasing points");
    }
  }

  const auto by_error = [](const Interval& x, const Interval& y) { return x.error < y.error; };
  std::priority_queue<Interval, std::vector<Interval>, decltype(by_error)> open(by_error);
  std::vector<Interval> settled;  // intervals that bisection cannot improve any more
  QuadratureResult result;
  for (std::size_t i = 1; i < breakpoints.size(); ++i) {
    if (breakpoints[i] == breakpoints[i - 1]) continue;
    Interval piece = kronrod21(f, breakpoints[i - 1], breakpoints[i]);
    result.evaluations += 21;
    if (piece.improvable) {
      open.push(piece);
    } else {
      settled.push_back(piece);
    }
  }

  // Running totals are only used to decide when to stop; the result is summed afresh below.
  const auto totals = [&](double& value, double& error) {
    value = 0.0;
    error = 0.0;
    auto copy = open;
    while (!copy.empty()) {
      value += copy.top().value;
      error += copy.top().error;
      copy.pop();
    }
    for (const Interval& piece : settled) {
      value += piece.value;
      error += piece.error;
    }
  };
  double value = 0.0;
  double error = 0.0;
  totals(value, error);
  const auto tolerance = [&](double v) {
    return std::max(options.abs_tol, options.rel_tol * std::abs(v));
  };
  int count = static_cast<int>(open.size() + settled.size());
  while (error > tolerance(value) && !open.empty() && count < options.max_intervals) {
    const Interval worst = open.top();
    open.pop();
    const double mid = 0.5 * (worst.a + worst.b);
    const Interval lower = kronrod21(f, worst.a, mid);
    const Interval upper = kronrod21(f, mid, worst.b);
    result.evaluations += 42;
    ++count;
    value += lower.value + upper.value - worst.value;
    error += lower.error + upper.error - worst.error;
    for (const Interval& piece : {lower, upper}) {
      if (piece.improvable) {
        open.push(piece);
      } else {
        settled.push_back(piece);
      }
    }
  }

  totals(value, error);
  const bool nothing_to_bisect = open.empty();
  double abs_value = 0.0;
  for (const Interval& piece : settled) abs_value += piece.abs_value;
  while (!open.empty()) {
    abs_value += open.top().abs_value;
    open.pop();
  }
  result.value = value;
  result.error = error;
  result.abs_value = abs_value;
  result.intervals = count;
  result.converged = error <= tolerance(value);
  result.rounding_limited = !result.converged && nothing_to_bisect;
  return result;
}

QuadratureResult integrate_adaptive(const std::function<double(double)>& f, double a, double b,
                                    const QuadratureOptions& options) {
  const std::array<double, 2> ends = {a, b};
  return integrate_adaptive(f, ends, options);
}

// n-point Gauss-Legendre rule by Newton's method on P_n from the Chebyshev guess
// (Press et al., Numerical Recipes, 3rd ed., §4.6.1, routine gauleg).
GaussLegendre gauss_legendre(int n) {
  GaussLegendre rule{std::vector<double>(static_cast<std::size_t>(n)),
                     std::vector<double>(static_cast<std::size_t>(n))};
  for (int i = 0; i < n; ++i) {
    double x = std::cos(pi * (i + 0.75) / (n + 0.5));
    double derivative = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0, p1 = 0.0;
      for (int k = 1; k <= n; ++k) {  // P_k by the three-term recurrence
        const double p2 = p1;
        p1 = p0;
        p0 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p2) / k;
      }
      derivative = n * (x * p0 - p1) / (x * x - 1.0);
      const double step = p0 / derivative;
      x -= step;
      if (std::abs(step) < 1e-15) break;
    }
    rule.nodes[static_cast<std::size_t>(i)] = x;
    rule.weights[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - x * x) * derivative * derivative);
  }
  return rule;
}

}  // namespace scatterlab
