#include "scatterlab/models/photon_beam_diffusion.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "radial_integrals.hpp"
#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/phase_function.hpp"
#include "scatterlab/core/quadrature.hpp"
#include "scatterlab/models/boundary_reflection.hpp"

namespace scatterlab {
namespace {

// Optical depths (in sigma_t' or sigma_t) beyond which exp(-x) < 2e-22 adds nothing.
constexpr double cutoff_mfp = 50.0;
constexpr double point_tol = 1e-9;   // relative tolerance of the outer integrals
constexpr double inner_tol = 1e-11;  // and of the inner one (the annulus correction)

// Integral of f from breaks[0] to breaks[1]; the other breakpoints, where inside, split it.
double integrate(const std::function<double(double)>& f, std::vector<double> breaks, double tol) {
  const double from = breaks[0], to = breaks[1];
  std::erase_if(breaks, [&](double b) { return !(b >= from && b <= to); });
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  QuadratureOptions options;
  options.rel_tol = tol;
  options.abs_tol = 1e-300;
  return integrate_adaptive(f, breaks, options).value;
}

// Breakpoints from `from` to the cutoff, for an integrand decaying at `rate` beyond `from` whose
// features sit at distance ~`width` from it: {from, cutoff, then the features}.
std::vector<double> breaks_from(double from, double rate, double width) {
  std::vector<double> breaks{from, from + cutoff_mfp / rate, from + 1.0 / rate, from + 5.0 / rate};
  for (const double f : {0.25, 1.0, 4.0}) breaks.push_back(from + f * width);
  return breaks;
}

// Q(t) = alpha' sigma_t' exp(-sigma_t' t).
double first_collisions(const PhotonBeamDiffusion& m, double t) {
  return m.medium.reduced_albedo() * m.sigma_t_reduced * std::exp(-m.sigma_t_reduced * t);
}

// 1 - kappa(t, r) = exp(-2 sigma_t' (d_r + t)) (PBD eq. 12).
double not_kappa(const PhotonBeamDiffusion& m, double t, double r) {
  return std::exp(-2.0 * m.sigma_t_reduced * (std::hypot(r, t) + t));
}

// int_r0^r1 (1 - kappa) R_dipole 2 pi r dr for the source at depth t: what kappa takes from the
// dipole's closed-form annulus integral. (1 - kappa) <= exp(-2 sigma_t' r), so r beyond
// cutoff / (2 sigma_t') adds nothing.
double kappa_correction(const PhotonBeamDiffusion& m, const DipoleModel& dipole, double t,
                        double r0, double r1) {
  const double end = std::min(r1, r0 + cutoff_mfp / (2.0 * m.sigma_t_reduced) + t);
  if (!(end > r0)) return 0.0;
  const auto f = [&](double r) {
    return 2.0 * pi * r * not_kappa(m, t, r) * dipole_reflectance(dipole, r);
  };
  std::vector<double> breaks{r0, end, t};
  for (const double f_t : {0.25, 4.0}) breaks.push_back(f_t * t);
  return integrate(f, breaks, inner_tol);
}

}  // namespace

PhotonBeamDiffusion photon_beam_diffusion(const HalfSpaceMedium& medium) {
  medium.validate();
  PhotonBeamDiffusion m;
  m.medium = medium;
  m.sigma_t_reduced = medium.reduced_sigma_t();
  const double s = m.sigma_t_reduced;
  DipoleModel& d = m.source;
  d.strength = medium.reduced_albedo();
  d.diffusion = (2.0 * medium.sigma_a + medium.reduced_sigma_s()) / (3.0 * s * s);  // Grosjean
  d.sigma_tr = std::sqrt(medium.sigma_a / d.diffusion);
  d.source_depth = 0.0;
  d.image_height = 4.0 * better_boundary_a(medium.eta) * d.diffusion;  // 2 z_b, z_b = 2 A D
  d.fluence_weight = exitance_fluence_weight(medium.eta);
  d.flux_weight = exitance_flux_weight(medium.eta);
  return m;
}

DipoleModel photon_beam_diffusion_source(const PhotonBeamDiffusion& m, double depth) {
  DipoleModel dipole = m.source;
  dipole.source_depth = depth;
  dipole.image_height = depth + m.source.image_height;
  return dipole;
}

double photon_beam_diffusion_reflectance(const PhotonBeamDiffusion& m, double r) {
  detail::check_radius(r);
  if (m.source.strength == 0.0) return 0.0;
  if (r == 0.0) return HUGE_VAL;  // ~ log(1 / r) (header)
  const auto f = [&](double t) {
    return first_collisions(m, t) * (1.0 - not_kappa(m, t, r)) *
           dipole_reflectance(photon_beam_diffusion_source(m, t), r);
  };
  return integrate(f, breaks_from(0.0, m.sigma_t_reduced, r), point_tol);
}

double photon_beam_diffusion_single(const PhotonBeamDiffusion& m, double r) {
  detail::check_radius(r);
  const HalfSpaceMedium& medium = m.medium;
  if (medium.sigma_s == 0.0) return 0.0;
  if (r == 0.0) return HUGE_VAL;  // ~ 1 / r (header)
  const double sigma_t = medium.sigma_t();
  const double t_c = medium.eta > 1.0 ? r * std::sqrt(medium.eta * medium.eta - 1.0) : 0.0;
  const HenyeyGreenstein phase{medium.g};
  const auto f = [&](double t) {
    const double d = std::hypot(r, t), mu = t / d;
    // Scattered from +z (down the beam) toward the surface point: cos = -t / d. Leaving the
    // medium the relative index is n_outside / n_medium = 1 / eta.
    return medium.sigma_s * std::exp(-sigma_t * (t + d)) * phase.evaluate(-mu) *
           fresnel_dielectric_transmittance(mu, 1.0 / medium.eta) * mu / (d * d);
  };
  return integrate(f, breaks_from(t_c, sigma_t, r), point_tol);
}

double photon_beam_diffusion_annulus_integral(const PhotonBeamDiffusion& m, double r0, double r1) {
  if (m.source.strength == 0.0) return 0.0;
  const auto f = [&](double t) {
    const DipoleModel dipole = photon_beam_diffusion_source(m, t);
    return first_collisions(m, t) * (dipole_reflectance_annulus_integral(dipole, r0, r1) -
                                     kappa_correction(m, dipole, t, r0, r1));
  };
  std::vector<double> breaks = breaks_from(0.0, m.sigma_t_reduced, r0);
  breaks.push_back(r1);
  return integrate(f, breaks, point_tol);
}

double photon_beam_diffusion_total_reflectance(const PhotonBeamDiffusion& m) {
  if (m.source.strength == 0.0) return 0.0;
  const auto f = [&](double t) {
    const DipoleModel dipole = photon_beam_diffusion_source(m, t);
    return first_collisions(m, t) *
           (dipole_total_reflectance(dipole) - kappa_correction(m, dipole, t, 0.0, HUGE_VAL));
  };
  return integrate(f, breaks_from(0.0, m.sigma_t_reduced, 1.0 / m.sigma_t_reduced), point_tol);
}

std::vector<double> photon_beam_diffusion_annulus_average(const PhotonBeamDiffusion& m,
                                                          std::span<const double> r_edges) {
  return detail::annulus_averages(r_edges, [&](double r0, double r1) {
    return photon_beam_diffusion_annulus_integral(m, r0, r1);
  });
}

}  // namespace scatterlab
