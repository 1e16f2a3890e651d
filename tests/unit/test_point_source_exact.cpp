// The exact point-source solution (models/point_source_exact) and the adaptive quadrature it
// rests on (core/quadrature). The contour form is checked against two independent inversions
// of the same Fourier transform, c A^2 / (1 - c A) with A = arctan(k) / k:
//   - a 30-digit table computed once with mpmath (quad + quadosc on the Fourier integral, the
//     large-k asymptote c pi^2 / (4 k^2) subtracted analytically), reproduced below;
//   - a double-precision oscillatory inversion done here, half period by half period with
//     Wynn's epsilon acceleration of the partial sums.
// and against conservation identities that hold for any correct solution.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/quadrature.hpp"
#include "scatterlab/models/point_source_exact.hpp"

namespace scatterlab {
namespace {

double relative_difference(double value, double reference) {
  return std::abs(value - reference) / std::abs(reference);
}

// ---------------------------------------------------------------------------------------------
// Quadrature.

TEST(PointSourceQuadrature, KronrodRuleIsExactToDegree31AndGaussToDegree19) {
  QuadratureOptions one_panel;
  one_panel.max_intervals = 1;  // report the first 21-point estimate, no bisection
  one_panel.rel_tol = 0.0;
  for (int degree = 0; degree <= 31; ++degree) {
    const auto f = [degree](double x) { return std::pow(x, degree); };
    const double exact = degree % 2 == 1 ? 0.0 : 2.0 / (degree + 1);
    const QuadratureResult r = integrate_adaptive(f, -1.0, 1.0, one_panel);
    EXPECT_NEAR(r.value, exact, 4e-16) << "degree " << degree;
    EXPECT_EQ(r.evaluations, 21);
  }
  // Degree 20 is the first that the embedded 10-point Gauss rule misses: the error estimate,
  // built from |Kronrod - Gauss|, must see it.
  const QuadratureResult r20 =
      integrate_adaptive([](double x) { return std::pow(x, 20); }, -1.0, 1.0, one_panel);
  EXPECT_GT(r20.error, 1e-10);
  // Degree 32 is beyond the Kronrod rule itself.
  const QuadratureResult r32 =
      integrate_adaptive([](double x) { return std::pow(x, 32); }, -1.0, 1.0, one_panel);
  EXPECT_GT(std::abs(r32.value - 2.0 / 33.0), 1e-14);
}

TEST(PointSourceQuadrature, AdaptiveReachesToleranceOnHardIntegrands) {
  QuadratureOptions options;
  options.rel_tol = 1e-13;
  // Square-root end point singularity.
  const QuadratureResult root =
      integrate_adaptive([](double x) { return std::sqrt(x); }, 0.0, 1.0, options);
  EXPECT_TRUE(root.converged);
  EXPECT_NEAR(root.value, 2.0 / 3.0, 1e-13);
  // A sharp Lorentzian: int_-1^1 dx / (x^2 + e^2) = 2 atan(1 / e) / e.
  const double e = 1e-3;
  const QuadratureResult peak =
      integrate_adaptive([e](double x) { return 1.0 / (x * x + e * e); }, -1.0, 1.0, options);
  EXPECT_TRUE(peak.converged);
  EXPECT_LT(relative_difference(peak.value, 2.0 * std::atan(1.0 / e) / e), 1e-12);
  // Breakpoints: |x - 1/3| on [0, 1] with the kink as a breakpoint is one panel per side.
  const std::array<double, 3> kink = {0.0, 1.0 / 3.0, 1.0};
  const QuadratureResult abs_value =
      integrate_adaptive([](double x) { return std::abs(x - 1.0 / 3.0); }, kink, options);
  EXPECT_NEAR(abs_value.value, 1.0 / 18.0 + 2.0 / 9.0, 1e-15);
  EXPECT_EQ(abs_value.evaluations, 42);
}

TEST(PointSourceQuadrature, RejectsUnusableBreakpoints) {
  const auto f = [](double x) { return x; };
  const std::array<double, 1> one = {0.0};
  const std::array<double, 3> decreasing = {0.0, 2.0, 1.0};
  const std::array<double, 2> infinite = {0.0, std::numeric_limits<double>::infinity()};
  for (const std::span<const double> points :
       {std::span<const double>(one), std::span<const double>(decreasing),
        std::span<const double>(infinite)}) {
    try {
      integrate_adaptive(f, points);
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& error) {
      EXPECT_EQ(error.field(), "breakpoints");
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Independent inversion of the Fourier integral, in double precision.
//
// phi_c(rho) = 1 / (2 pi^2 rho) int_0^inf k sin(k rho) F(k) dk, F = c A^2 / (1 - c A). At large k,
// k F ~ c pi^2 / (4 k); the smooth stand-in s k / (1 + k^2), s = c pi^2 / 4, whose sine
// transform is s (pi / 2) exp(-rho) (the 3-D pair 1 / (1 + k^2) <-> exp(-r) / (4 pi r)
// through the radial inversion formula), is subtracted so that the
// rest decays as 1 / k^2. That rest is integrated over [0, K0] (K0 >= 40, a multiple of the half
// period pi / rho) and then half period by half period; the alternating partial sums are
// extrapolated with Wynn's epsilon algorithm (Wynn 1956, "On a device for computing the
// e_m(S_n) transformation").

double wynn_epsilon(const std::vector<double>& sums) {
  const std::size_t n = sums.size();
  std::vector<double> previous(n, 0.0);  // column k - 1, starting with eps_{-1} = 0
  std::vector<double> current = sums;    // column k, starting with eps_0 = the sums
  double estimate = sums.back();
  for (std::size_t k = 1; k < n; ++k) {
    std::vector<double> next(n - k);
    for (std::size_t j = 0; j + k < n; ++j) {
      const double difference = current[j + 1] - current[j];
      if (difference == 0.0) return current[j + 1];  // converged exactly
      next[j] = previous[j + 1] + 1.0 / difference;
    }
    previous = current;
    current = next;
    if (k % 2 == 0) estimate = current.back();  // even columns estimate the limit
  }
  return estimate;
}

double fourier_transform_collided(double c, double k) {
  const double a = k < 1e-4 ? 1.0 - k * k / 3.0 : std::atan(k) / k;
  return c * a * a / (1.0 - c * a);
}

double fourier_collided_fluence(double c, double rho) {
  const double s = c * pi * pi / 4.0;
  const auto integrand = [c, rho, s](double k) {
    return (k * fourier_transform_collided(c, k) - s * k / (1.0 + k * k)) * std::sin(k * rho);
  };
  QuadratureOptions options;
  options.rel_tol = 1e-14;
  options.abs_tol = 1e-300;
  options.max_intervals = 20000;

  const double half_period = pi / rho;
  const int first_periods = std::max(1, static_cast<int>(std::ceil(40.0 / half_period)));
  std::vector<double> breaks;
  for (int i = 0; i <= first_periods; ++i) breaks.push_back(i * half_period);
  // The transform has a Lorentzian-like peak of width sqrt(3 (1 - c)) at k = 0.
  const double width = std::sqrt(3.0 * (1.0 - c));
  for (const double f : {0.25, 0.5, 1.0, 2.0, 4.0}) breaks.push_back(f * width);
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::remove_if(breaks.begin(), breaks.end(),
                              [&](double x) { return x > first_periods * half_period; }),
               breaks.end());
  double sum = integrate_adaptive(integrand, breaks, options).value;

  std::vector<double> partial_sums = {sum};
  for (int j = 0; j < 24; ++j) {
    const double a = (first_periods + j) * half_period;
    sum += integrate_adaptive(integrand, a, a + half_period, options).value;
    partial_sums.push_back(sum);
  }
  const double oscillatory = wynn_epsilon(partial_sums);
  return (oscillatory + s * 0.5 * pi * std::exp(-rho)) / (2.0 * pi * pi * rho);
}

// ---------------------------------------------------------------------------------------------
// The contour form against the Fourier inversions.

struct Reference {
  double albedo;
  double rho;
  double collided;  // phi_collided, W mfp^-2 per W
};

// mpmath 1.3 at 30 digits: I = int_0^inf sin(k rho) [k F(k) - c pi^2 / (4 k)] dk by mp.quad on
// [0, 1] (split at multiples of sqrt(3 (1 - c))) plus mp.quadosc on [1, inf), then
// phi_c = (I + c pi^3 / 8) / (2 pi^2 rho). A 30-digit evaluation of the contour form agreed
// with every entry to better than 1e-25 relative.
constexpr std::array<Reference, 30> high_precision_references = {{
    {0.01, 0.05, 0.03336368590931842572},   {0.01, 0.3, 0.0033492402730046089242},
    {0.01, 1.0, 0.00034838894620680972553}, {0.01, 3.0, 9.52156052411469581e-6},
    {0.01, 10.0, 1.2538863338142006458e-9}, {0.3, 0.05, 1.0418875907929867561},
    {0.3, 0.3, 0.11511685412164858594},     {0.3, 1.0, 0.013858913066571104548},
    {0.3, 3.0, 0.00047574205374919685081},  {0.3, 10.0, 9.2401357909757637315e-8},
    {0.5, 0.05, 1.791207301055188814},      {0.5, 0.3, 0.21420358510302877333},
    {0.5, 1.0, 0.029420221750844014938},    {0.5, 3.0, 0.0012819898212434212219},
    {0.5, 10.0, 4.2473898114579372351e-7},  {0.9, 0.05, 3.4952815640616341299},
    {0.9, 0.3, 0.52832957383797097587},     {0.9, 1.0, 0.11400894576329317094},
    {0.9, 3.0, 0.013699821793396606582},    {0.9, 10.0, 0.00010486104578235678299},
    {0.99, 0.05, 3.9748820071097342946},    {0.99, 0.3, 0.67634317657312581439},
    {0.99, 1.0, 0.19091965678163532451},    {0.99, 3.0, 0.046492992179598210204},
    {0.99, 10.0, 0.004185056227015814907},  {0.9999, 0.05, 4.0572498461238023442},
    {0.9999, 0.3, 0.72173844846650181387},  {0.9999, 1.0, 0.22760694763479623052},
    {0.9999, 3.0, 0.075356130394983840878}, {0.9999, 10.0, 0.020073468936989325481},
}};

TEST(PointSourceExact, CollidedFluenceMatchesHighPrecisionFourierInversion) {
  double worst = 0.0;
  for (const Reference& ref : high_precision_references) {
    const double value = point_source_fluence_collided(ref.albedo, ref.rho);
    const double difference = relative_difference(value, ref.collided);
    worst = std::max(worst, difference);
    EXPECT_LT(difference, 1e-11) << "c = " << ref.albedo << ", rho = " << ref.rho;
  }
  std::cout << "[ contour vs 30-digit Fourier: worst relative difference " << worst << " ]\n";
}

TEST(PointSourceExact, CollidedFluenceMatchesDoublePrecisionFourierInversion) {
  double worst = 0.0;
  for (const double c : {0.01, 0.3, 0.5, 0.9, 0.99}) {
    for (const double rho : {0.05, 0.3, 1.0, 3.0, 10.0}) {
      const double contour = point_source_fluence_collided(c, rho);
      const double fourier = fourier_collided_fluence(c, rho);
      const double difference = relative_difference(contour, fourier);
      worst = std::max(worst, difference);
      EXPECT_LT(difference, 1e-10) << "c = " << c << ", rho = " << rho;
    }
  }
  std::cout << "[ contour vs double-precision Fourier: worst relative difference " << worst
            << " ]\n";
}

// ---------------------------------------------------------------------------------------------
// Conservation identities. From the transform at k = 0 (A = 1 - k^2/3 + O(k^4)):
//   int phi dV = F(0) = 1 / (1 - c)   (sigma_t = 1: collisions per source photon; the
//                                      uncollided part gives 1, so the collided part c / (1 - c)),
//   int rho^2 phi dV = -laplacian F(0) = 2 / (1 - c)^2, i.e. <rho^2> of the absorption point
//   (density (1 - c) phi) is 2 / (1 - c): a geometric number N of flights, E[N] = 1 / (1 - c),
//   each with <l^2> = 2 and independent isotropic directions, so E|R|^2 = 2 E[N].
// The uncollided parts are exactly 1 and int rho^2 exp(-rho) drho = 2.

// int_0^inf 4 pi rho^2 rho^power phi_collided(rho) drho from point values, by adaptive
// quadrature on a doubling grid out to where exp(-rho / nu0) < 1e-30.
double collided_moment_from_points(double c, int power) {
  const double nu0 = discrete_eigenvalue(c);
  const double end = 70.0 * nu0 + 40.0;
  std::vector<double> breaks = {0.0};
  for (double x = 0.01; x < end; x *= 2.0) breaks.push_back(x);
  breaks.push_back(end);
  QuadratureOptions options;
  options.rel_tol = 1e-12;
  const QuadratureResult result = integrate_adaptive(
      [c, power](double rho) {
        if (rho == 0.0) return 0.0;
        return 4.0 * pi * rho * rho * std::pow(rho, power) * point_source_fluence_collided(c, rho);
      },
      breaks, options);
  return result.value;
}

TEST(PointSourceExact, EverythingIsAbsorbed) {
  for (const double c : {0.01, 0.3, 0.5, 0.9, 0.99}) {
    const double collided = collided_moment_from_points(c, 0);
    EXPECT_LT(relative_difference(collided, c / (1.0 - c)), 1e-10) << "c = " << c;
    EXPECT_LT(relative_difference((1.0 - c) * (1.0 + collided), 1.0), 1e-10) << "c = " << c;
  }
  // The same through the closed-form shell integral over (0, inf), including extreme albedos.
  for (const double c : {0.0, 1e-12, 0.01, 0.3, 0.9, 0.99, 0.9999, 1.0 - 1e-8}) {
    const double total = point_source_fluence_shell_integral(c, 0.0, INFINITY);
    EXPECT_LT(relative_difference((1.0 - c) * total, 1.0), 1e-11) << "c = " << c;
    if (c > 0.0) {
      const double collided = point_source_fluence_shell_integral(c, 0.0, INFINITY, false);
      EXPECT_LT(relative_difference(collided, c / (1.0 - c)), 1e-10) << "c = " << c;
    }
  }
}

TEST(PointSourceExact, MeanSquaredDistanceOfAbsorption) {
  for (const double c : {0.01, 0.3, 0.5, 0.9, 0.99}) {
    const double collided = collided_moment_from_points(c, 2);
    EXPECT_LT(relative_difference(collided, 2.0 / ((1.0 - c) * (1.0 - c)) - 2.0), 1e-10)
        << "c = " << c;
    EXPECT_LT(relative_difference((1.0 - c) * (2.0 + collided), 2.0 / (1.0 - c)), 1e-10)
        << "c = " << c;
  }
}

// ---------------------------------------------------------------------------------------------
// Shell averages.

// Shell integral of the collided fluence from point values (independent of the closed-form
// rho integration used by the model).
double collided_shell_integral_from_points(double c, double rho0, double rho1) {
  QuadratureOptions options;
  options.rel_tol = 1e-13;
  return integrate_adaptive(
             [c](double rho) {
               return rho == 0.0 ? 0.0
                                 : 4.0 * pi * rho * rho * point_source_fluence_collided(c, rho);
             },
             rho0, rho1, options)
      .value;
}

TEST(PointSourceExact, ShellAverageMatchesQuadratureOfPointValues) {
  struct Shell {
    double rho0, rho1;
  };
  const std::array<Shell, 7> shells = {
      {{0.0, 0.05}, {0.0, 10.0}, {0.05, 0.1}, {0.95, 1.0}, {2.0, 4.0}, {9.95, 10.0}, {9.0, 30.0}}};
  for (const double c : {0.01, 0.5, 0.9, 0.99, 0.9999}) {
    for (const Shell& shell : shells) {
      const double volume = 4.0 / 3.0 * pi * (std::pow(shell.rho1, 3) - std::pow(shell.rho0, 3));
      const double expected_collided =
          collided_shell_integral_from_points(c, shell.rho0, shell.rho1) / volume;
      const double collided = point_source_fluence_shell_average(c, shell.rho0, shell.rho1, false);
      EXPECT_LT(relative_difference(collided, expected_collided), 1e-10)
          << "c = " << c << ", shell [" << shell.rho0 << ", " << shell.rho1 << ")";
      const double uncollided = (std::exp(-shell.rho0) - std::exp(-shell.rho1)) / volume;
      const double total = point_source_fluence_shell_average(c, shell.rho0, shell.rho1);
      EXPECT_TRUE(std::isfinite(total));
      EXPECT_LT(relative_difference(total, expected_collided + uncollided), 1e-10)
          << "c = " << c << ", shell [" << shell.rho0 << ", " << shell.rho1 << ")";
    }
  }
}

TEST(PointSourceExact, ShellsAddUpAndThinShellsTendToPointValues) {
  const double c = 0.7;
  // 200 shells of 0.05 mfp over [0, 10): their integrals add up to the whole ball.
  double sum = 0.0;
  for (int i = 0; i < 200; ++i) {
    sum += point_source_fluence_shell_integral(c, 0.05 * i, 0.05 * (i + 1));
  }
  EXPECT_LT(relative_difference(sum, point_source_fluence_shell_integral(c, 0.0, 10.0)), 1e-12);
  // A shell of width h averages phi over [rho, rho + h]: the value at its volume-weighted
  // mid-point to O(h^2).
  for (const double rho : {0.05, 1.0, 10.0}) {
    const double h = 1e-6 * rho;
    const double average = point_source_fluence_shell_average(c, rho, rho + h);
    EXPECT_LT(relative_difference(average, point_source_fluence(c, rho + 0.5 * h)), 1e-9)
        << "rho = " << rho;
  }
}

// ---------------------------------------------------------------------------------------------
// Extreme albedos.

TEST(PointSourceExact, DiscreteEigenvalueSolvesItsEquation) {
  // 1 = c nu0 artanh(1 / nu0). Rounding nu0 to a double (half an ulp, eps nu0 / 2) moves the
  // left side by c |d/dnu (nu artanh(1/nu))| eps nu0 / 2, with d/dnu = artanh(1/nu) -
  // nu / (nu^2 - 1), which is large as nu0 -> 1: the tolerance follows that conditioning.
  constexpr double eps = std::numeric_limits<double>::epsilon();
  for (const double c : {0.1, 0.2, 0.3, 0.5, 0.9, 0.99, 0.9999, 1.0 - 1e-10}) {
    const double nu0 = discrete_eigenvalue(c);
    ASSERT_GT(nu0, 1.0) << "c = " << c;
    const double slope = std::abs(std::atanh(1.0 / nu0) - nu0 / ((nu0 - 1.0) * (nu0 + 1.0)));
    const double tolerance = 1e-14 + 2.0 * c * slope * eps * nu0;
    EXPECT_NEAR(c * nu0 * std::atanh(1.0 / nu0), 1.0, tolerance) << "c = " << c;
  }
  // mpmath (findroot on u / tanh u = 1 / c at 30 digits, nu0 = coth u) at the decimal c; the
  // double nearest 0.99 differs from it by ~1e-17, which moves nu0 ~ (1 - c)^(-1/2) by up to
  // ~3e-15 relative, hence the tolerance.
  EXPECT_LT(relative_difference(discrete_eigenvalue(0.3), 1.0025928887932231991), 1e-14);
  EXPECT_LT(relative_difference(discrete_eigenvalue(0.5), 1.044382033760833485), 1e-14);
  EXPECT_LT(relative_difference(discrete_eigenvalue(0.9), 1.903204856044847719), 1e-14);
  EXPECT_LT(relative_difference(discrete_eigenvalue(0.99), 5.7967294513020023098), 1e-14);
  // Diffusion limit: 3 (1 - c) nu0^2 = c (1 + 3 / (5 nu0^2) + ...) from the series of
  // nu artanh(1/nu) = 1 + 1/(3 nu^2) + 1/(5 nu^4) + ..., so nu0 sqrt(3 (1 - c)) -> 1 with
  // relative corrections of order 1 - c. (1 - c is taken from the stored c, not from 1e-10.)
  const double c_high = 1.0 - 1e-10;
  EXPECT_NEAR(discrete_eigenvalue(c_high) * std::sqrt(3.0 * (1.0 - c_high)), 1.0, 1e-9);
  // Small c: nu0 - 1 ~ 2 exp(-2/c) is below the spacing of doubles near 1 for c < ~0.05, so
  // nu0 rounds to 1; no NaN, no infinity.
  for (const double c : {0.0, 1e-300, 1e-12, 1e-3, 0.02}) {
    const double nu0 = discrete_eigenvalue(c);
    EXPECT_TRUE(std::isfinite(nu0)) << "c = " << c;
    EXPECT_EQ(nu0, 1.0) << "c = " << c;
  }
  EXPECT_TRUE(std::isfinite(discrete_eigenvalue(std::numeric_limits<double>::denorm_min())));
  // Increasing in c.
  double previous = 1.0;
  for (double c = 0.1; c < 1.0; c += 0.05) {
    const double nu0 = discrete_eigenvalue(c);
    EXPECT_GT(nu0, previous) << "c = " << c;
    previous = nu0;
  }
}

TEST(PointSourceExact, ZeroAlbedoHasNoCollidedLight) {
  for (const double rho : {1e-3, 0.05, 1.0, 10.0, 100.0}) {
    EXPECT_EQ(point_source_fluence_collided(0.0, rho), 0.0);
    EXPECT_EQ(point_source_fluence(0.0, rho), point_source_fluence_uncollided(rho));
  }
  EXPECT_EQ(point_source_fluence_shell_average(0.0, 0.0, 1.0, false), 0.0);
  EXPECT_DOUBLE_EQ(point_source_fluence_uncollided(2.0), std::exp(-2.0) / (16.0 * pi));
}

TEST(PointSourceExact, SmallAlbedoIsFirstOrderInAlbedo) {
  // phi_collided = c phi_1 + O(c^2): phi_collided / c at c = 1e-10 and 1e-13 agree to ~1e-10,
  // and nothing is lost to underflow of the discrete mode.
  for (const double rho : {0.05, 1.0, 10.0}) {
    const double a = point_source_fluence_collided(1e-10, rho) / 1e-10;
    const double b = point_source_fluence_collided(1e-13, rho) / 1e-13;
    EXPECT_GT(a, 0.0);
    EXPECT_LT(relative_difference(a, b), 1e-8) << "rho = " << rho;
    EXPECT_TRUE(std::isfinite(point_source_fluence_collided(1e-300, rho)));
    EXPECT_GT(point_source_fluence_collided(1e-300, rho), 0.0);
  }
  // Near rho = 0, single scattering gives phi_collided -> c pi / (16 rho) (the large-k
  // asymptote c pi^2 / (4 k^2) of the transform).
  const double rho = 1e-7;
  EXPECT_LT(relative_difference(point_source_fluence_collided(0.3, rho), 0.3 * pi / (16.0 * rho)),
            1e-5);
}

TEST(PointSourceExact, AlbedoNearOneIsFinite) {
  for (const double c : {0.9999, 1.0 - 1e-8}) {
    for (const double rho : {1e-3, 0.05, 1.0, 10.0, 1000.0}) {
      const double value = point_source_fluence(c, rho);
      EXPECT_TRUE(std::isfinite(value) && value > 0.0) << "c = " << c << ", rho = " << rho;
    }
    EXPECT_TRUE(std::isfinite(point_source_fluence_shell_average(c, 0.0, 0.05)));
  }
  // Far out the diffusion mode dominates: phi -> P exp(-rho / nu0) / (4 pi rho), P -> 3.
  const double c = 1.0 - 1e-8;
  const double nu0 = discrete_eigenvalue(c);
  const double rho = 100.0;
  EXPECT_NEAR(point_source_fluence(c, rho) * 4.0 * pi * rho / std::exp(-rho / nu0), 3.0, 1e-6);
}

// ---------------------------------------------------------------------------------------------
// Input checks.

template <typename Call>
void expect_input_error(Call call, const std::string& field) {
  try {
    call();
    ADD_FAILURE() << "no InputError for " << field;
  } catch (const InputError& error) {
    EXPECT_EQ(error.field(), field);
    EXPECT_NE(std::string(error.what()).find("accepted"), std::string::npos);
  }
}

TEST(PointSourceExact, BadInputThrowsInputError) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const double albedo : {-0.1, 1.0, 1.5, nan, inf}) {
    expect_input_error([&] { discrete_eigenvalue(albedo); }, "albedo");
    expect_input_error([&] { point_source_fluence_collided(albedo, 1.0); }, "albedo");
    expect_input_error([&] { point_source_fluence(albedo, 1.0); }, "albedo");
    expect_input_error([&] { point_source_fluence_shell_average(albedo, 0.0, 1.0); }, "albedo");
  }
  for (const double rho : {0.0, -1.0, nan, inf}) {
    expect_input_error([&] { point_source_fluence_uncollided(rho); }, "rho");
    expect_input_error([&] { point_source_fluence_collided(0.5, rho); }, "rho");
    expect_input_error([&] { point_source_fluence(0.5, rho); }, "rho");
  }
  expect_input_error([&] { point_source_fluence_shell_average(0.5, -0.1, 1.0); }, "rho0");
  expect_input_error([&] { point_source_fluence_shell_average(0.5, nan, 1.0); }, "rho0");
  expect_input_error([&] { point_source_fluence_shell_average(0.5, 1.0, 1.0); }, "rho1");
  expect_input_error([&] { point_source_fluence_shell_average(0.5, 2.0, 1.0); }, "rho1");
  expect_input_error([&] { point_source_fluence_shell_average(0.5, 0.0, nan); }, "rho1");
  expect_input_error([&] { point_source_fluence_shell_average(0.5, 0.0, inf); }, "rho1");
  expect_input_error([&] { point_source_fluence_shell_integral(0.5, 1.0, 0.5); }, "rho1");
}

// ---------------------------------------------------------------------------------------------
// Cost: the Monte Carlo comparison evaluates ~200 shells per albedo.

TEST(PointSourceExact, TwoHundredShellsTakeWellUnderASecond) {
  for (const double c : {0.01, 0.99}) {
    const auto start = std::chrono::steady_clock::now();
    double sink = 0.0;
    for (int i = 0; i < 200; ++i) {
      sink += point_source_fluence_shell_average(c, 0.05 * i, 0.05 * (i + 1));
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_TRUE(std::isfinite(sink));
    EXPECT_LT(seconds, 0.5) << "c = " << c;
    std::cout << "[ 200 shell averages at c = " << c << ": " << seconds * 1e3 << " ms ]\n";
  }
}

}  // namespace
}  // namespace scatterlab
