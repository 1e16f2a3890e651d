#include "scatterlab/models/point_source_exact.hpp"

// Derivation (reproduced in full because the numbers below depend on every step; the method is
// that of Case, de Hoffmann & Placzek 1953, vol. I, the infinite-medium point source, and of
// Case & Zweifel 1967, "Linear Transport Theory", the infinite-medium Green's function; also
// d'Eon 2016, "A Hitchhiker's Guide to Multiple Scattering", the 3-D isotropic point source.
// Equation numbers in those texts were not checked here; every step is verified numerically in
// tests/unit/test_point_source_exact.cpp instead).
//
// (D1) Integral equation. With sigma_t = 1 the collision density equals the fluence phi, the
//      scattered emission density is c phi, and an isotropic emission at r' gives fluence
//      K(|r - r'|) = exp(-|r - r'|) / (4 pi |r - r'|^2) at r. So phi = K + c K * phi.
// (D2) Fourier transform (f^(k) = int f(r) exp(-i k.r) dV): K^(k) = int_0^inf exp(-r)
//      sin(kr) / (kr) dr = arctan(k) / k =: A(k), hence phi^ = A / (1 - c A); the collided part
//      is phi^ - A = c A^2 / (1 - c A). For a radial function the inverse transform is
//      phi(rho) = 1 / (2 pi^2 rho) int_0^inf k sin(k rho) phi^(k) dk.
// (D3) Contour. phi^ is even in k, so int_0^inf k sin(k rho) F dk = (1 / 2i) int_R k
//      exp(i k rho) F dk. Close in the upper half plane: arctan(k) = (1 / 2i) log((1 + i k) /
//      (1 - i k)) has its cut on k = i s, s > 1, and 1 - c A vanishes at k = i / nu0 with
//      c nu0 artanh(1 / nu0) = 1 (on k = i s, s < 1, A = artanh(s) / s). The total and the
//      collided transforms differ by A, which has no pole, so both have the same residue.
// (D4) Pole. With u = artanh(1 / nu0) (so nu0 = coth u and the root condition reads
//      c u = tanh u), the residue gives
//        phi_pole(rho) = P exp(-rho / nu0) / (4 pi rho),
//        P = 2 (nu0^2 - 1) / (c nu0^2 (1 - (1 - c) nu0^2)) = 2 u^2 tanh u / (sinh u cosh u - u).
//      Checks: P -> 3 as c -> 1 (diffusion, D = 1/3); P ~ 8 u^2 exp(-2u) -> 0 as c -> 0.
// (D5) Cut. On k = i s (s = 1 / nu > 1) from the right and left, arctan = +-pi/2 + i artanh(nu),
//      so A_+- = a -+ i b with a = nu artanh(nu), b = pi nu / 2. The jump of A / (1 - c A) is
//      -2 i b / D with D = |1 - c A_+|^2 = (1 - c a)^2 + (c b)^2, and walking both banks gives
//        phi_cut,total(rho)    = 1 / (4 pi rho) int_0^1 exp(-rho / nu) / (nu^2 D(nu)) dnu,
//        phi_cut,collided(rho) = 1 / (4 pi rho) int_0^1 exp(-rho / nu) W(nu) dnu,
//        W(nu) = (1 / D - 1) / nu^2 = c (2 a - c (a^2 + b^2)) / (nu^2 D).
//      Check: at c = 0 the total cut integral is int_1^inf exp(-s rho) ds / (4 pi rho)
//      = exp(-rho) / (4 pi rho^2), the uncollided fluence, and W = 0.
// (D6) So phi_collided(rho) = [P exp(-rho / nu0) + int_0^1 W(nu) exp(-rho / nu) dnu] / (4 pi rho).
//      W is bounded (W(0) = c (2 - c pi^2 / 4), W -> -1 as nu -> 1), and the integral is
//      done in t = artanh(nu) (nu = tanh t, dnu = sech^2 t dt, a = t tanh t), where the
//      logarithmic end at nu = 1 becomes an exponentially decaying tail and the near-resonance
//      c a = 1 (at t ~ 1/c for small c) is an O(1)-wide bump: smooth for adaptive quadrature.
// (D7) Shells. Each term of (D6) is (1 / (4 pi rho)) exp(-rho / nu); times 4 pi rho^2 and
//      integrated over rho0 <= rho < rho1 it gives M(nu) = int_rho0^rho1 rho exp(-rho / nu) drho
//      in closed form, so the shell integral of the collided fluence is
//        P M(nu0) + int_0^1 W(nu) M(nu) dnu,
//      one quadrature of the same cost as a point value (no nested quadrature over rho).

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/quadrature.hpp"

namespace scatterlab {
namespace {

// Upper end of the t = artanh(nu) integral. Beyond it sech^2 t < 4 exp(-60) ~ 3.5e-26 and
// exp(-rho / nu) <= exp(-rho). Away from the resonance c t tanh t = 1, |W| is ~ 2 c t (small c)
// or <= ~1 (c t >> 1); near it |W| can reach ~ 8 / (pi c)^2, but for c < 1/30 that region sits
// at t ~ 1/c where sech^2 t ~ 4 exp(-2 / c). The dropped tail is thus < ~1e-20 of the integral.
constexpr double t_max = 30.0;

// Relative accuracy asked of the branch-cut quadrature.
constexpr double cut_rel_tol = 1e-13;

void check_albedo(double albedo) {
  if (!(albedo >= 0.0 && albedo < 1.0)) {
    throw InputError("albedo", "got " + std::to_string(albedo), "a number in [0, 1)");
  }
}

void check_rho(double rho) {
  if (!(rho > 0.0) || !std::isfinite(rho)) {
    throw InputError("rho", "got " + std::to_string(rho), "a finite number > 0 (mfp)");
  }
}

// u coth u - 1, accurate for small u: u cosh u - sinh u = sum_{n>=1} 2n u^(2n+1) / (2n+1)!
// (Taylor series of cosh and sinh), divided by sinh u; the direct form cancels as u -> 0.
double u_coth_u_minus_one(double u) {
  if (u >= 1.0) return u / std::tanh(u) - 1.0;
  const double u2 = u * u;
  double term = u;  // u^(2n+1) / (2n+1)! for n = 0
  double sum = 0.0;
  for (int n = 1; n <= 12; ++n) {
    term *= u2 / static_cast<double>((2 * n) * (2 * n + 1));
    sum += static_cast<double>(2 * n) * term;
  }
  return sum / std::sinh(u);
}

// sinh u cosh u - u = (sinh 2u - 2u) / 2 = sum_{n>=1} (2u)^(2n+1) / (2 (2n+1)!) (Taylor series
// of sinh), for small u where the direct form cancels.
double sinh_cosh_minus_u(double u) {
  if (u >= 1.0) return 0.5 * std::sinh(2.0 * u) - u;
  const double x = 2.0 * u;
  const double x2 = x * x;
  double term = x;
  double sum = 0.0;
  for (int n = 1; n <= 14; ++n) {
    term *= x2 / static_cast<double>((2 * n) * (2 * n + 1));
    sum += term;
  }
  return 0.5 * sum;
}

// The discrete mode of (D3)-(D4) in the variable u = artanh(1 / nu0) in (0, inf), root of
// c u = tanh u, i.e. u coth u - 1 = (1 - c) / c. The left side is increasing and convex in u,
// and (1 - c) / c is exact enough near c = 1 (1 - c is exact there), so u keeps full relative
// precision as c -> 1 (u ~ sqrt(3 (1 - c))) where nu0 itself is large.
struct DiscreteMode {
  double u = std::numeric_limits<double>::infinity();  // infinite for c = 0
  double decay = 1.0;      // 1 / nu0 = tanh u, the decay rate of exp(-rho / nu0)
  double amplitude = 0.0;  // P of (D4)
};

DiscreteMode discrete_mode(double c) {
  DiscreteMode mode;
  if (c == 0.0) return mode;
  const double target = (1.0 - c) / c;
  double u = 1.0 / c;
  if (u < 20.0) {
    // Newton from u = 1/c, which lies above the root (u coth u - 1 > u - 1): on an increasing
    // convex function the iterates then decrease monotonically to the root.
    for (int iteration = 0; iteration < 100; ++iteration) {
      const double s = std::sinh(u);
      const double derivative = sinh_cosh_minus_u(u) / (s * s);  // d/du (u coth u)
      const double step = (u_coth_u_minus_one(u) - target) / derivative;
      u -= step;
      if (std::abs(step) <= 1e-15 * u) break;
    }
  }
  // For u >= 20, tanh u = 1 - 2 exp(-2u) rounds to 1, so the root of c u = tanh u is u = 1/c to
  // relative 2 exp(-40).
  mode.u = u;
  mode.decay = std::tanh(u);
  if (u < 20.0) {
    mode.amplitude = 2.0 * u * u * mode.decay / sinh_cosh_minus_u(u);
  } else {
    // P = 8 u^2 tanh(u) exp(-2u) / (1 - 4 u exp(-2u) - exp(-4u)) from (D4) with
    // sinh u cosh u = (exp(2u) - exp(-2u)) / 4; taken through logs so that u^2 cannot overflow
    // (u = 1/c up to 1e308): it underflows to 0 for u > ~370, i.e. c < ~0.0027.
    const double e2 = std::exp(-2.0 * u);
    mode.amplitude = std::exp(std::log(8.0) + 2.0 * std::log(u) - 2.0 * u) * mode.decay /
                     (1.0 - 4.0 * u * e2 - e2 * e2);
  }
  return mode;
}

// W(nu) sech^2(t) at nu = tanh t: the collided cut weight of (D5) times the Jacobian of
// nu = tanh t.
double cut_weight_dt(double c, double t) {
  const double nu = std::tanh(t);
  const double cosh_t = std::cosh(t);
  const double jacobian = 1.0 / (cosh_t * cosh_t);
  if (nu < 1e-100) return c * (2.0 - c * pi * pi / 4.0) * jacobian;  // W(0), nu^2 would underflow
  const double a = t * nu;                                           // nu artanh(nu)
  const double b = 0.5 * pi * nu;
  const double one_minus_ca = 1.0 - c * a;
  const double d = one_minus_ca * one_minus_ca + c * c * b * b;
  return c * (2.0 * a - c * (a * a + b * b)) / (nu * nu * d) * jacobian;
}

// 1 - (1 + y) exp(-y) = sum_{n>=2} (-1)^n (n - 1) y^n / n! (Taylor series of exp), for small y
// where the direct form cancels.
double one_minus_one_plus_y_exp(double y) {
  if (y >= 1.0) return 1.0 - (1.0 + y) * std::exp(-y);
  double power = -y;  // (-y)^n / n!, here for n = 1
  double sum = 0.0;
  for (int n = 2; n <= 22; ++n) {
    power *= -y / static_cast<double>(n);
    sum += static_cast<double>(n - 1) * power;
  }
  return sum;
}

// M(nu) = int_rho0^rho1 rho exp(-rho / nu) drho of (D7). With x0 = rho0 / nu, y = (rho1 - rho0)
// / nu: M = nu^2 exp(-x0) [x0 (1 - exp(-y)) + 1 - (1 + y) exp(-y)], written so that a thin
// shell (small y) does not cancel. rho1 = +inf gives nu^2 exp(-x0) (1 + x0).
double shell_moment(double nu, double rho0, double rho1) {
  const double x0 = rho0 / nu;
  const double head = nu * nu * std::exp(-x0);
  if (head == 0.0) return 0.0;
  if (std::isinf(rho1)) return head * (1.0 + x0);
  const double y = (rho1 - rho0) / nu;
  return head * (-x0 * std::expm1(-y) + one_minus_one_plus_y_exp(y));
}

// int_0^t_max g(t) dt with breakpoints on a doubling grid: the integrand's features sit at
// t ~ rho (where exp(-rho / tanh t) switches on) and at t ~ log(rho) / 2 (where it peaks for
// large rho), both covered by some cell of the grid.
double cut_integral(const std::function<double(double)>& g, double abs_tol) {
  static constexpr std::array<double, 12> breaks = {0.0, 0.03125, 0.0625, 0.125, 0.25, 0.5,
                                                    1.0, 2.0,     4.0,    8.0,   16.0, t_max};
  QuadratureOptions options;
  options.rel_tol = cut_rel_tol;
  options.abs_tol = abs_tol;
  options.max_intervals = 2000;
  const QuadratureResult result = integrate_adaptive(g, breaks, options);
  if (!result.converged && !result.rounding_limited) {
    throw std::runtime_error("point_source_exact: branch-cut quadrature did not converge (error " +
                             std::to_string(result.error) + " on " + std::to_string(result.value) +
                             ")");
  }
  return result.value;
}

}  // namespace

double discrete_eigenvalue(double albedo) {
  check_albedo(albedo);
  // nu0 = coth u (D4); 1 for c = 0, where u is infinite.
  return 1.0 / discrete_mode(albedo).decay;
}

double point_source_fluence_uncollided(double rho) {
  check_rho(rho);
  // (D1): the kernel itself, exp(-rho) / (4 pi rho^2).
  return std::exp(-rho) * inv_four_pi / (rho * rho);
}

double point_source_fluence_collided(double albedo, double rho) {
  check_albedo(albedo);
  check_rho(rho);
  if (albedo == 0.0) return 0.0;  // c A^2 / (1 - c A) = 0 (D2)
  const double c = albedo;
  const DiscreteMode mode = discrete_mode(c);
  // (D6): discrete mode plus branch cut, both over 4 pi rho.
  const double pole = mode.amplitude * std::exp(-rho * mode.decay);
  const double cut = cut_integral(
      [c, rho](double t) {
        const double nu = std::tanh(t);
        const double attenuation = std::exp(-rho / nu);
        return attenuation == 0.0 ? 0.0 : cut_weight_dt(c, t) * attenuation;
      },
      cut_rel_tol * std::abs(pole));
  return (pole + cut) * inv_four_pi / rho;
}

double point_source_fluence(double albedo, double rho) {
  return point_source_fluence_uncollided(rho) + point_source_fluence_collided(albedo, rho);
}

double point_source_fluence_shell_integral(double albedo, double rho0, double rho1,
                                           bool include_uncollided) {
  check_albedo(albedo);
  const std::string accepted = "0 <= rho0 < rho1, rho0 finite (mfp)";
  if (!(rho0 >= 0.0) || !std::isfinite(rho0)) {
    throw InputError("rho0", "got " + std::to_string(rho0), accepted);
  }
  if (!(rho1 > rho0)) {
    throw InputError("rho1", "got " + std::to_string(rho1) + " with rho0 = " + std::to_string(rho0),
                     accepted);
  }
  // Uncollided: int 4 pi rho^2 exp(-rho) / (4 pi rho^2) drho = exp(-rho0) - exp(-rho1) (D1),
  // as exp(-rho0) (1 - exp(-(rho1 - rho0))) so that thin shells do not cancel.
  double total = 0.0;
  if (include_uncollided) {
    total += std::isinf(rho1) ? std::exp(-rho0) : -std::exp(-rho0) * std::expm1(rho0 - rho1);
  }
  if (albedo == 0.0) return total;
  const double c = albedo;
  const DiscreteMode mode = discrete_mode(c);
  // (D7): P M(nu0) + int W M dnu.
  const double pole =
      mode.amplitude == 0.0 ? 0.0 : mode.amplitude * shell_moment(1.0 / mode.decay, rho0, rho1);
  const double cut = cut_integral(
      [c, rho0, rho1](double t) {
        const double moment = shell_moment(std::tanh(t), rho0, rho1);
        return moment == 0.0 ? 0.0 : cut_weight_dt(c, t) * moment;
      },
      cut_rel_tol * std::abs(pole));
  return total + pole + cut;
}

double point_source_fluence_shell_average(double albedo, double rho0, double rho1,
                                          bool include_uncollided) {
  check_albedo(albedo);
  if (!std::isfinite(rho1)) {
    throw InputError("rho1", "got " + std::to_string(rho1), "a finite number > rho0 (mfp)");
  }
  const double integral =
      point_source_fluence_shell_integral(albedo, rho0, rho1, include_uncollided);
  // 4/3 pi (rho1^3 - rho0^3), factored so that a thin shell does not cancel.
  const double volume = 4.0 / 3.0 * pi * (rho1 - rho0) * (rho1 * rho1 + rho1 * rho0 + rho0 * rho0);
  return integral / volume;
}

}  // namespace scatterlab
