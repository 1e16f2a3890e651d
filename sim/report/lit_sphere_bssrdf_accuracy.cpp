// The lit sphere's BSSRDF integral (models/lit_sphere_exitance.hpp: Bitterli eq. 2.14 with eq.
// 2.16 over the lit hemisphere, sampled along the profile and along the light) against a
// deterministic nested quadrature of the same integral (lit_sphere_exitance_quadrature), which
// shares nothing with the sampling but the profile and the Fresnel term.

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/models/diffusion_profile.hpp"
#include "scatterlab/models/half_space_medium.hpp"
#include "scatterlab/models/lit_sphere_exitance.hpp"
#include "scatterlab/report/suites.hpp"
#include "simulation_checks.hpp"

namespace scatterlab::report {
namespace {

struct Timed {
  LitSphereExitance exitance;
  double seconds = 0.0;
};

Timed timed_exitance(const DiffusionProfile& profile, double radius,
                     const std::vector<double>& edges, int samples, std::uint64_t seed) {
  const auto start = std::chrono::steady_clock::now();
  Timed t{lit_sphere_exitance(profile, radius, edges, samples, seed), 0.0};
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return t;
}

}  // namespace

Section lit_sphere_bssrdf_convergence(const Profile& profile) {
  Section section;
  section.id = "lit_sphere_bssrdf_convergence";
  section.title = "Lit sphere BSSRDF integral: error against run time";
  constexpr double albedo = 0.9, g = 0.0, eta = 1.3, radius = 2.0;
  const DiffusionProfile model(ProfileModel::better_dipole,
                               HalfSpaceMedium::from_albedo(albedo, g, eta));
  const std::vector<double> edges{0.0, pi / 4.0, pi / 2.0, 3.0 * pi / 4.0, pi};
  const double lit = lit_sphere_exitance_quadrature(model, radius, edges[0], edges[1]);
  const double shadow = lit_sphere_exitance_quadrature(model, radius, edges[3], edges[4]);
  section.reference = fmt::format(
      "The better dipole's exitance on a sphere of radius {} mfp (albedo {}, g {}, eta {}) under "
      "the directional light, averaged over psi in [0, pi/4] (lit pole) and [3 pi/4, pi] "
      "(shadow): {:.9g} and {:.9g} per mfp^2 per unit power meeting the sphere, by nested "
      "quadrature (Gauss-Legendre in cos psi_o, adaptive Gauss-Kronrod in psi_i and the azimuth).",
      radius, albedo, g, eta, lit, shadow);
  section.tolerance =
      "Each budget within 5 standard errors of the quadrature; the standard error falls as "
      "N^-1/2 (slope in [-0.6, -0.4]). The quadrature itself: 8 and 16 Gauss-Legendre nodes "
      "agree to 1e-6.";
  for (const auto& [name, lo, hi, value] : {std::tuple{"lit pole", edges[0], edges[1], lit},
                                            std::tuple{"shadow", edges[3], edges[4], shadow}}) {
    const double finer = lit_sphere_exitance_quadrature(model, radius, lo, hi, 16);
    section.checks.push_back(
        {fmt::format("{}: quadrature with 8 nodes {:.10g}, with 16 {:.10g}", name, value, finer),
         std::abs(finer - value) <= 1e-6 * std::abs(finer)});
  }
  add_error_against_run_time(
      section, profile,
      {{"exitance_lit_pole", "$M$ at the lit pole", lit},
       {"exitance_shadow", "$M$ in the shadow", shadow}},
      fmt::format("Better dipole on a sphere, R = {:g} mfp, eta {:g}", radius, eta),
      [&](std::uint64_t samples, std::uint64_t seed) {
        const Timed t = timed_exitance(model, radius, edges, static_cast<int>(samples), seed);
        return scalar_output(
            t.seconds, {{"exitance_lit_pole", {t.exitance.mean[0], t.exitance.stderr_of_mean[0]}},
                        {"exitance_shadow", {t.exitance.mean[3], t.exitance.stderr_of_mean[3]}}});
      },
      {"samples_per_bin", "samples per bin"});
  return section;
}

Section lit_sphere_bssrdf_extremes(const Profile& profile) {
  Section section;
  section.id = "lit_sphere_bssrdf_extremes";
  section.title = "Lit sphere BSSRDF integral: stiff and extreme cases";
  section.reference =
      "The dipole's and the better dipole's exitance on the lit and the shadowed hemisphere, "
      "sampled, against the nested quadrature of the same integral.";
  section.tolerance =
      "Each hemisphere within 5 standard errors of the quadrature; no NaN or Inf; an eta the "
      "BSSRDF cannot take refused, naming the field.";
  section.table.columns = {
      "model", "albedo",         "eta",   "radius_mfp", "samples",           "seconds",
      "lit",   "lit_quadrature", "lit_z", "shadow",     "shadow_quadrature", "shadow_z"};
  struct Cell {
    double albedo, eta, radius;
  };
  std::vector<Cell> cells;
  for (const double albedo : {1e-6, 0.5, 1.0 - 1e-6}) cells.push_back({albedo, 1.3, 2.0});
  // The BSSRDF's exit term takes eta up to 2 (models/bssrdf.hpp): 2.5 is refused below.
  for (const double eta : {1.0001, 2.0}) cells.push_back({0.9, eta, 2.0});
  for (const double radius : {0.05, 50.0}) cells.push_back({0.9, 1.3, radius});
  const std::vector<double> edges{0.0, pi / 2.0, pi};
  const int samples = profile.quick ? 20'000 : 200'000;
  // Quantized diffusion's profile, a sum of Gaussians, costs the nested quadrature minutes per
  // cell; its sampling is the same code as the dipoles', and its profile is held against its
  // continuum in model_continua.
  for (const ProfileModel m : {ProfileModel::dipole, ProfileModel::better_dipole}) {
    for (const Cell& c : cells) {
      const DiffusionProfile model(m, HalfSpaceMedium::from_albedo(c.albedo, 0.0, c.eta));
      const std::uint64_t seed = profile.seed + section.table.rows.size();
      const Timed t = timed_exitance(model, c.radius, edges, samples, seed);
      std::vector<std::string> row = {to_string(m),
                                      fmt::format("{}", c.albedo),
                                      fmt::format("{}", c.eta),
                                      fmt::format("{}", c.radius),
                                      fmt::format("{}", samples),
                                      fmt::format("{:.3g}", t.seconds)};
      for (std::size_t b = 0; b < 2; ++b) {
        const Estimate e{t.exitance.mean[b], t.exitance.stderr_of_mean[b]};
        const double exact =
            lit_sphere_exitance_quadrature(model, c.radius, edges[b], edges[b + 1]);
        section.non_finite_values +=
            !std::isfinite(e.mean) + !std::isfinite(e.stderr_of_mean) + !std::isfinite(exact);
        section.checks.push_back(
            {fmt::format("{}, albedo {}, eta {}, R {} mfp, {} hemisphere: {:.6g} against "
                         "quadrature {:.6g}",
                         to_string(m), c.albedo, c.eta, c.radius, b == 0 ? "lit" : "shadowed",
                         e.mean, exact),
             agrees(e, exact, samples)});
        row.insert(row.end(), {fmt::format("{:.6g}", e.mean), fmt::format("{:.6g}", exact),
                               fmt::format("{:.2f}", z_score(e, exact))});
      }
      section.table.rows.push_back(std::move(row));
    }
  }
  std::string refusal = "none";
  try {
    const DiffusionProfile model(ProfileModel::better_dipole,
                                 HalfSpaceMedium::from_albedo(0.9, 0.0, 2.5));
    timed_exitance(model, 2.0, edges, 2, profile.seed);
  } catch (const InputError& e) {
    refusal = e.field();
  }
  section.checks.push_back(
      {fmt::format("eta 2.5, beyond the exit term's fits: refused, naming \"{}\"", refusal),
       refusal == "eta"});
  section.findings = checks_over_cells(section);
  return section;
}

}  // namespace scatterlab::report
