#include "scatterlab/models/dipole.hpp"

#include <array>
#include <cmath>
#include <string>

#include "radial_integrals.hpp"
#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/quadrature.hpp"
#include "scatterlab/models/boundary_reflection.hpp"

namespace scatterlab {
namespace {

// The parts both dipoles share once D and A are chosen (Bitterli §2.5).
DipoleModel make_dipole(const HalfSpaceMedium& medium, double diffusion, double a) {
  DipoleModel model;
  const double sigma_t_reduced = medium.reduced_sigma_t();
  model.strength = medium.reduced_albedo();
  model.diffusion = diffusion;
  model.sigma_tr = std::sqrt(medium.sigma_a / diffusion);
  model.source_depth = 1.0 / sigma_t_reduced;                    // Bitterli eq. 2.35
  model.image_height = model.source_depth + 4.0 * a * diffusion;  // z_v = z_r + 2 z_b
  return model;
}

void check_point(double r, double z) {
  if (!(r >= 0.0) || !std::isfinite(r)) {
    throw InputError("r", "got " + std::to_string(r), "a finite number >= 0");
  }
  if (!(z >= 0.0) || !std::isfinite(z)) {
    throw InputError("z", "got " + std::to_string(z), "a finite depth >= 0 (inside the medium)");
  }
}

// exp(-s d) / d, +infinity at d = 0.
double green(double s, double d) { return d == 0.0 ? HUGE_VAL : std::exp(-s * d) / d; }

}  // namespace

DipoleModel classical_dipole(const HalfSpaceMedium& medium) {
  medium.validate();
  // Jensen et al. 2001: D = 1 / (3 sigma_t') (Bitterli eq. 2.22), A from F_dr (eq. 2.30).
  DipoleModel model = make_dipole(medium, 1.0 / (3.0 * medium.reduced_sigma_t()),
                                  classical_boundary_a(medium.eta));
  model.fluence_weight = 0.0;
  model.flux_weight = 1.0;
  return model;
}

DipoleModel better_dipole(const HalfSpaceMedium& medium) {
  medium.validate();
  // d'Eon 2012: D = (2 sigma_a + sigma_s') / (3 sigma_t'^2), A = (1 + 3 C_2) / (1 - 2 C_1).
  const double st = medium.reduced_sigma_t();
  DipoleModel model = make_dipole(medium,
                                  (2.0 * medium.sigma_a + medium.reduced_sigma_s()) / (3.0 * st * st),
                                  better_boundary_a(medium.eta));
  // Strength alpha'^2: the light scattered at least twice (dipole.hpp says why).
  model.strength = medium.reduced_albedo() * medium.reduced_albedo();
  model.fluence_weight = exitance_fluence_weight(medium.eta);
  model.flux_weight = exitance_flux_weight(medium.eta);
  return model;
}

double dipole_reflectance(const DipoleModel& m, double r) {
  check_point(r, 0.0);
  const double s = m.sigma_tr;
  const double dr = std::hypot(r, m.source_depth);
  const double dv = std::hypot(r, m.image_height);
  // Bitterli eq. 2.37 (normal flux) and eq. 2.33 at z = 0 (fluence), weighted by C_E, C_phi.
  const double flux = m.source_depth * (1.0 + s * dr) * std::exp(-s * dr) / (dr * dr * dr) +
                      m.image_height * (1.0 + s * dv) * std::exp(-s * dv) / (dv * dv * dv);
  const double fluence = (std::exp(-s * dr) / dr - std::exp(-s * dv) / dv) / m.diffusion;
  return m.strength * inv_four_pi * (m.flux_weight * flux + m.fluence_weight * fluence);
}

double dipole_fluence(const DipoleModel& m, double r, double z) {
  check_point(r, z);
  if (m.strength == 0.0) return 0.0;  // not 0 * infinity at the source point
  const double dr = std::hypot(r, z - m.source_depth);
  const double dv = std::hypot(r, z + m.image_height);
  return m.strength * inv_four_pi / m.diffusion * (green(m.sigma_tr, dr) - green(m.sigma_tr, dv));
}

double dipole_total_reflectance(const DipoleModel& m) {
  const double s = m.sigma_tr;
  // int E 2 pi r dr: 2 pi z int (1 + s d) exp(-s d) / d^2 dd = 2 pi exp(-s z) from d = z to inf
  // (the integrand is -d/dd [exp(-s d) / d]), for each source; int phi(r, 0) 2 pi r dr =
  // 2 pi / (4 pi D) int_{z_r}^{z_v} ... = exp_integral_linear over [z_r, z_v] / (2 D).
  const double e_r = std::exp(-s * m.source_depth);
  const double e_v = std::exp(-s * m.image_height);
  const double flux = 0.5 * (e_r + e_v);
  const double fluence = 0.5 / m.diffusion * detail::exp_integral_linear(s, m.source_depth, m.image_height);
  return m.strength * (m.flux_weight * flux + m.fluence_weight * fluence);
}

double dipole_reflectance_annulus_integral(const DipoleModel& m, double r0, double r1) {
  const double s = m.sigma_tr;
  double flux = 0.0, fluence = 0.0;
  for (const auto& [height, sign] :
       {std::pair{m.source_depth, 1.0}, std::pair{m.image_height, -1.0}}) {
    const double d0 = std::hypot(r0, height), d1 = std::hypot(r1, height);
    // 2 pi z [exp(-s d) / d] from d1 to d0, the antiderivative noted in the total above.
    flux += 2.0 * pi * height * (std::exp(-s * d0) / d0 - std::exp(-s * d1) / d1);
    fluence += sign * 2.0 * pi * detail::exp_integral_linear(s, d0, d1) / m.diffusion;
  }
  return m.strength * inv_four_pi * (m.flux_weight * flux + m.fluence_weight * fluence);
}

double dipole_fluence_annulus_integral(const DipoleModel& m, double r0, double r1, double z) {
  const double s = m.sigma_tr;
  // 2 pi int exp(-s d) / d r dr = 2 pi int exp(-s d) dd over each source's distance range.
  const double real = detail::exp_integral_linear(s, std::hypot(r0, z - m.source_depth),
                                                  std::hypot(r1, z - m.source_depth));
  const double image = detail::exp_integral_linear(s, std::hypot(r0, z + m.image_height),
                                                   std::hypot(r1, z + m.image_height));
  return m.strength * inv_four_pi / m.diffusion * 2.0 * pi * (real - image);
}

std::vector<double> dipole_reflectance_annulus_average(const DipoleModel& m,
                                                      std::span<const double> r_edges) {
  return detail::annulus_averages(r_edges, [&](double r0, double r1) {
    return dipole_reflectance_annulus_integral(m, r0, r1);
  });
}

std::vector<double> dipole_fluence_cell_average(const DipoleModel& m,
                                                std::span<const double> r_edges,
                                                std::span<const double> z_edges) {
  detail::check_edges(r_edges, "r_edges");
  detail::check_edges(z_edges, "z_edges");
  const std::size_t nr = r_edges.size() - 1, nz = z_edges.size() - 1;
  std::vector<double> average(nr * nz);
  QuadratureOptions options;
  options.rel_tol = 1e-10;
  for (std::size_t i = 0; i < nr; ++i) {
    const double r0 = r_edges[i], r1 = r_edges[i + 1];
    const auto radial = [&](double z) { return dipole_fluence_annulus_integral(m, r0, r1, z); };
    for (std::size_t j = 0; j < nz; ++j) {
      const double z0 = z_edges[j], z1 = z_edges[j + 1];
      // The r0 = 0 integrand has a kink at the source depth: split there.
      std::vector<double> breaks{z0};
      if (m.source_depth > z0 && m.source_depth < z1) breaks.push_back(m.source_depth);
      breaks.push_back(z1);
      const double integral = integrate_adaptive(radial, breaks, options).value;
      average[i * nz + j] = integral / (pi * (r1 * r1 - r0 * r0) * (z1 - z0));
    }
  }
  return average;
}

}  // namespace scatterlab
