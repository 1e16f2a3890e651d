#pragma once
// Quantized diffusion (d'Eon & Irving 2011, "A quantized-diffusion model for rendering
// translucent materials", SIGGRAPH 2011) for the searchlight problem: the multiply-scattered
// diffuse reflectance R_d(r) and fluence phi(r, z) of a half-space under a normal pencil beam,
// as a sum of Gaussians in r.
//
// What it models (reduced coefficients, similarity relations, Bitterli eqs. 2.23-2.24):
//  - the extended source: the beam's first collisions at depth z' > 0 have density
//    sigma_t' exp(-sigma_t' z') per unit power entering the medium;
//  - Grosjean's modification (Grosjean 1956, as d'Eon & Irving use it): light leaving a first
//    collision uncollided is the once-scattered part, not modelled here; what is modelled is the
//    light scattered at least twice, so each first collision is a diffusion source of strength
//    alpha'^2 (one alpha' for the beam's collision, one for the next; models/dipole.hpp says why
//    the better dipole carries the same factor), with Grosjean's
//    D = (2 sigma_a + sigma_s') / (3 sigma_t'^2);
//  - the better dipole's boundary (d'Eon 2012; models/boundary_reflection.hpp): each source at z'
//    has a negative image at -(z' + d_e), d_e = 2 z_b = 4 A D, A = (1 + 3 C_2) / (1 - 2 C_1), and
//    the exitance is R = C_phi phi + C_E D dphi/dz at z = 0;
//  - time quantization: the steady Green's function exp(-sigma_tr rho) / (4 pi D rho) is the
//    time integral (t as path length, unit speed) of the time-resolved one,
//    (4 pi D t)^(-3/2) exp(-rho^2 / (4 D t)) exp(-sigma_a t), a 3-D Gaussian of variance
//    v = 2 D t per axis. The time axis is cut into intervals [t_i, t_i+1); each becomes one
//    Gaussian of variance v_i = 2 D t_i* and weight w_i ~ int exp(-sigma_a t) dt over the
//    interval, t_i* a point of the interval ("Time grid" below says which point and why).
//
// A 3-D Gaussian factorises into a 2-D one in r and a 1-D one in depth, so the integral over the
// extended source is closed-form per Gaussian. With g1(v, x) = exp(-x^2 / 2v) / sqrt(2 pi v),
// g2(v, r) = exp(-r^2 / 2v) / (2 pi v), s = sigma_t' and
//   J(v, d) = int_0^inf s exp(-s z') g1(v, z' + d) dz'
//           = (s / 2) exp(s d + s^2 v / 2) erfc((d + s v) / sqrt(2 v))      (complete the square)
//           = (s / 2) exp(-d^2 / 2v) erfcx((d + s v) / sqrt(2 v))          (the stable form),
// the surface values are
//   phi(r, 0)      = sum_i w_i g2(v_i, r) alpha'^2 [J(v_i, 0) - J(v_i, d_e)]
//   D dphi/dz(r,0) = sum_i w_i g2(v_i, r) alpha'^2 D s [g1(v_i, 0) - J(v_i, 0)
//                                                    + g1(v_i, d_e) - J(v_i, d_e)]
// (the flux term by parts: int s e^{-s z} (z + d) / v g1(z + d) dz = s g1(d) - s J(d)), and
//   R_d(r) = C_phi phi(r, 0) + C_E D dphi/dz(r, 0).
// Inside the medium, phi(r, z) = sum_i w_i g2(v_i, r) alpha'^2 [K(v_i, z) - J(v_i, z + d_e)] with
//   K(v, z) = int_0^inf s exp(-s z') g1(v, z - z') dz'
//           = (s / 2) exp(-s z + s^2 v / 2) erfc((s v - z) / sqrt(2 v)).
//
// As the intervals shrink, the sum tends to the time integral, which is the depth integral of
// better-dipole point sources (strength alpha'^2 each) along the beam: that limit is the
// independent evaluation the tests hold the sum against.
//
// Time grid: t_0 = 0, t_1 small, t_i+1 = q t_i. With u = ln t the time integral of any of the
// quantities above is int F(u) du, F = t exp(-sigma_a t) G(2 D t), where G (a surface or annulus
// term of one Gaussian) depends on t through exp(-c / t), powers of t and erfcx: F is analytic
// in the strip |Im u| < pi / 2 and decays at both ends. On the geometric grid the u-steps are
// equal, h = ln q, and the midpoint rule with equal steps on such an integrand converges as
// exp(-2 pi (pi / 2) / h) = exp(-pi^2 / h) (Trefethen & Weideman 2014, "The exponentially
// convergent trapezoidal rule", SIAM Review 56, the rule on the real line). So node i >= 1 sits
// at the interval's logarithmic mean t_i* = (t_i+1 - t_i) / h, with
//   v_i = 2 D t_i*,   w_i = (t_i+1 - t_i) exp(-sigma_a t_i*)   (= h t_i* exp(-sigma_a t_i*)),
// the interval length at sigma_a = 0. Node 1's u-cell starts at t_1' = t_1 (q - 1) / (h sqrt q);
// the first Gaussian covers [0, t_1'), where the flux term goes as t^(-1/2) (g1(v, 0) = 1 /
// sqrt(4 pi D t)): v_0 = D t_1' / 2 (the node at t_1' / 4, where t_1' (t_1' / 4)^(-1/2) =
// 2 sqrt(t_1') is that term's exact integral), w_0 = int_0^t_1' exp(-sigma_a t) dt.
// d'Eon & Irving's v_i = D (t_i + t_i+1) with w_i = int exp(-sigma_a t) dt is second order
// instead: on this grid F is nearly flat in u, f ~ 1 / t, and the arithmetic midpoint then errs
// by -(q - 1)^2 / 12 everywhere (measured -3.3e-5 at q = 1.02, which needs 1350-2100 Gaussians
// for 1e-4 where this rule needs 88-121).
// The sum stops once v >= 100 (11 / sigma_t' + d_e)^2 and the remaining total, bounded by
// F(t) min(2 t, 1 / sigma_a) (the total's integrand falls as t^(-3/2) exp(-sigma_a t) there),
// is below relative_tolerance / 8 of the continuum total. With eps = relative_tolerance:
// h = pi^2 / ln(1e5 / eps) (q = 1.85, 1.61, 1.48 at eps = 1e-2, 1e-4, 1e-6), or less in an
// absorbing medium, whose far annuli need h <= pi sqrt(2 / (X ln(1e3 / eps))), X = 10 sigma_tr /
// sigma_t' (the peak of their time integrand, quantized_diffusion.cpp), and
// t_1 = (1e-3 eps)^2 / (sigma_t'^2 D) (the midpoint rule's end correction at t_1',
// ~ h^2 / 48 F(t_1'), is then below eps / 100 of the innermost annulus stated below).
//
// Accuracy: annulus averages over edges in [0, 10 / sigma_t'] whose annuli reach at least
// 1e-3 / sigma_t', and the total, agree with that limit to `relative_tolerance`. Found by
// tests/unit/test_quantized_diffusion.cpp (albedo 0.5-1, g 0-0.9, eta 1-1.5, edges 0-10 mfp):
// worst 0.083 eps at eps = 1e-3 and 0.074 eps at 1e-4, both the total at albedo 1 (the cut
// tail); annulus averages within 0.03 eps, rings 0.1 / sigma_t' wide out to 10 / sigma_t' and
// albedos down to 0.01 included (eps = 1e-2 to 1e-6); fluence cell averages within 4e-9 at
// eps = 1e-4. Beyond 10 / sigma_t' the accuracy is not stated.
//
// Cost (Release, measured on a loaded 2-core machine): 54-90 Gaussians at eps = 1e-2, 88-135
// at 1e-4, 131-194 at 1e-6 (the most in strongly absorbing media); construction 2-10 us; a point
// value or the total 17-50 us (4 erfcx per Gaussian); 8 annulus averages 35-130 us; a 3 x 3 grid
// of fluence cells 0.6-3 ms (an adaptive z integral per Gaussian and z cell).
//
// Units as models/dipole.hpp: lengths in the medium's unit, R_d and phi in 1 / length^2 per
// unit power entering the medium (multiply by the entry transmittance for a tally per unit
// incident power). Normal incidence only. R_d(r) ~ 1 / r as r -> 0 (sources reach the surface),
// so R_d(0) = +infinity; annulus averages and the total are finite.

#include <span>
#include <vector>

#include "scatterlab/models/dipole.hpp"
#include "scatterlab/models/half_space_medium.hpp"

namespace scatterlab {

struct QuantizedDiffusion {
  double strength = 0.0;          // alpha'^2
  double sigma_t = 1.0;           // sigma_t', the extended source's decay, 1 / length
  double diffusion = 0.0;         // D (Grosjean), length
  double image_offset = 0.0;      // d_e = 4 A D, length
  double fluence_weight = 0.25;   // C_phi
  double flux_weight = 0.5;       // C_E
  std::vector<double> variance;   // v_i, length^2
  std::vector<double> weight;     // w_i, length
};

// relative_tolerance in [1e-6, 1e-2] (InputError "relative_tolerance" otherwise).
QuantizedDiffusion quantized_diffusion(const HalfSpaceMedium& medium,
                                       double relative_tolerance = 1e-4);

// R_d(r) per unit area, r >= 0 (+infinity at r = 0 unless alpha' = 0).
double quantized_diffusion_reflectance(const QuantizedDiffusion& model, double r);

// R_dr = int R_d 2 pi r dr (each Gaussian in r integrates to 1).
double quantized_diffusion_total_reflectance(const QuantizedDiffusion& model);

// Annulus averages of R_d (closed form per Gaussian); edges as dipole.hpp.
std::vector<double> quantized_diffusion_reflectance_annulus_average(
    const QuantizedDiffusion& model, std::span<const double> r_edges);

// Cell averages of phi over [r_i, r_i+1) x [z_j, z_j+1), row-major [r][z]; z edges >= 0.
std::vector<double> quantized_diffusion_fluence_cell_average(const QuantizedDiffusion& model,
                                                             std::span<const double> r_edges,
                                                             std::span<const double> z_edges);

// The continuum the sum approximates (its limit as the intervals shrink), evaluated
// independently of it: the depth integral, by adaptive quadrature to a relative 1e-10, of
// better-dipole point sources of strength alpha'^2 s exp(-s z) dz along the beam (s = sigma_t'),
// each with its image d_e above it (models/dipole.hpp's closed forms). The tests and `scatterlab
// report` hold the sum against it; it costs milliseconds where the sum costs microseconds.
class QuantizedDiffusionContinuum {
 public:
  explicit QuantizedDiffusionContinuum(const HalfSpaceMedium& medium);

  double total() const;                                // R_dr
  double annulus_average(double r0, double r1) const;  // R_d over r0 <= r < r1
  double fluence_cell_average(double r0, double r1, double z0, double z1) const;

 private:
  DipoleModel at(double depth) const;  // the point source at `depth` and its image
  // int_0^cutoff alpha'^2 s exp(-s z) f(z) dz, breaking the range at the given depths.
  template <class F>
  double depth_integral(F f, std::vector<double> breaks) const;

  double s_ = 1.0, strength_ = 0.0, cutoff_ = 50.0;
  DipoleModel base_;  // D, sigma_tr, C_phi, C_E of the better dipole
  double image_offset_ = 0.0;
};

}  // namespace scatterlab
