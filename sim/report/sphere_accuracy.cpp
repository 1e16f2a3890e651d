// The lit sphere's Monte Carlo (transport/lit_object.hpp) against its exact unscattered light.
//
// Light that enters a sphere meets its surface again at the angle it was refracted to, so every
// chord of its path has the same length L = 2 R cos theta_t and the same Fresnel reflectance F
// (from inside at theta_t it is F(theta_i) from outside: Born & Wolf §1.5.2, the reflectances
// are symmetric in the two angles). Before it first collides, light that entered is absorbed on a
// chord with 1 - e^-L, and at each end leaves with 1 - F or is reflected onto the next chord, so
// per unit power meeting the sphere at incidence theta_i (all lengths in mfp):
//   reflected at entry      F,
//   leaves unscattered      (1 - F)^2 e^-L / (1 - F e^-L),
//   first collides          (1 - F) (1 - e^-L) / (1 - F e^-L),
// the first collision absorbing a share 1 - albedo. A pencil beam at the pole has theta_i = 0; the
// directional light over the shadow disk has (b / R)^2 = sin^2 theta_i uniform in [0, 1], over
// which the exact values are integrated by adaptive Gauss-Kronrod quadrature (core/quadrature).
// With eta = 1 the directional light's first-collision share is the closed form
// 1 - (1 - (1 + 2R) e^-2R) / (2 R^2).

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/quadrature.hpp"
#include "scatterlab/report/suites.hpp"
#include "scatterlab/transport/lit_object.hpp"
#include "simulation_checks.hpp"

namespace scatterlab::report {
namespace {

// The exact unscattered fate of light meeting the sphere, per unit power meeting it.
struct Unscattered {
  double reflected = 0.0;  // at entry
  double leaves = 0.0;     // leaves without colliding
  double collides = 0.0;   // enters and collides at least once
};

Unscattered at_incidence(double cos_incident, double eta, double radius) {
  const FresnelDielectric surface = fresnel_dielectric_terms(cos_incident, eta);
  const double f = surface.reflectance();
  const double e = std::exp(-2.0 * radius * surface.cos_transmitted);
  const double round_trip = 1.0 - f * e;  // > 0: eta >= 1 never reflects totally at entry
  return {f, (1.0 - f) * (1.0 - f) * e / round_trip, (1.0 - f) * (1.0 - e) / round_trip};
}

Unscattered exact_unscattered(ObjectLight light, double eta, double radius) {
  if (light == ObjectLight::pole_beam) return at_incidence(1.0, eta, radius);
  QuadratureOptions options;
  options.rel_tol = 1e-11;
  const auto over_disk = [&](auto part) {
    return integrate_adaptive(
               [&](double u) { return part(at_incidence(std::sqrt(1.0 - u), eta, radius)); }, 0.0,
               1.0, options)
        .value;
  };
  return {over_disk([](const Unscattered& s) { return s.reflected; }),
          over_disk([](const Unscattered& s) { return s.leaves; }),
          over_disk([](const Unscattered& s) { return s.collides; })};
}

LitObjectSpec sphere_spec(double albedo, double g, double eta, double radius, ObjectLight light,
                          const RunSettings& run) {
  LitObjectSpec spec;
  spec.medium = Medium{albedo, 1.0, g, "mfp"};
  spec.eta = eta;
  spec.radius = radius;
  spec.light = light;
  spec.psi = UniformAxis{0.0, std::numbers::pi, 6};
  spec.run = run;
  return spec;
}

}  // namespace

Section sphere_convergence(const Profile& profile) {
  Section section;
  section.id = "sphere_convergence";
  section.title = "Lit sphere: error against run time";
  constexpr double albedo = 0.9, g = 0.5, eta = 1.33, radius = 1.0;
  const Unscattered exact = exact_unscattered(ObjectLight::directional, eta, radius);
  section.reference = fmt::format(
      "The light that leaves a sphere of radius {} mfp, eta {}, albedo {}, g {} under the "
      "directional light without colliding: the integral over the shadow disk of "
      "(1 - F)^2 e^-L / (1 - F e^-L), L = 2 R cos theta_t, = {:.9f} (adaptive quadrature).",
      radius, eta, albedo, g, exact.leaves);
  section.tolerance =
      "Each budget within 5 standard errors of the exact value; the standard error falls as "
      "N^-1/2 (least-squares slope of log stderr against log photons in [-0.6, -0.4]).";
  add_error_against_run_time(
      section, profile, {{"exited_unscattered", "the unscattered exitance", exact.leaves}},
      fmt::format("Sphere R = {:g} mfp, eta {:g}, directional light", radius, eta),
      [&](std::uint64_t photons, std::uint64_t seed) {
        return run_lit_sphere(sphere_spec(albedo, g, eta, radius, ObjectLight::directional,
                                          report_run(photons, seed, profile)));
      });
  return section;
}

Section sphere_extremes(const Profile& profile) {
  Section section;
  section.id = "sphere_extremes";
  section.title = "Lit sphere: stiff and extreme cases";
  section.reference =
      "Energy (reflected at entry + exited + absorbed = 1, and each by scattering order); the "
      "exact unscattered light: reflected at entry, leaving without a collision, and absorbed "
      "at the first collision, (1 - albedo) times the light that collides (chords of equal "
      "length and Fresnel reflectance; quadrature over the shadow disk for the directional "
      "light).";
  section.tolerance =
      "Energy to 1e-12; each unscattered part within 5 standard errors (the beam's reflection, "
      "which is exact, to 1e-12), or, where no photon was scored, an exact value below "
      "3 / photons. No NaN or Inf.";
  section.table.columns = {"light",
                           "albedo",
                           "g",
                           "eta",
                           "radius_mfp",
                           "photons",
                           "seconds",
                           "energy_residual",
                           "reflected_z",
                           "exited_unscattered",
                           "exited_exact",
                           "exited_z",
                           "absorbed_unscattered_z"};
  struct Cell {
    double albedo, g, eta, radius;
  };
  std::vector<Cell> cells;
  for (double albedo : {1e-6, 0.5, 1.0 - 1e-6}) {
    for (double g : {-0.999, 0.0, 0.999}) cells.push_back({albedo, g, 1.33, 1.0});
  }
  for (double eta : {1.0, 1.0001, 2.5}) cells.push_back({0.9, 0.5, eta, 1.0});
  for (double radius : {0.01, 10.0}) cells.push_back({0.9, 0.5, 1.33, radius});

  // The quadrature against the closed form of the matched sphere under the directional light.
  for (const double radius : {0.01, 1.0, 10.0}) {
    const double quadrature = exact_unscattered(ObjectLight::directional, 1.0, radius).collides;
    const double closed =
        1.0 - (1.0 - (1.0 + 2.0 * radius) * std::exp(-2.0 * radius)) / (2.0 * radius * radius);
    section.checks.push_back(
        {fmt::format("eta 1, R {} mfp: quadrature {:.12f} against the closed form {:.12f}", radius,
                     quadrature, closed),
         std::abs(quadrature - closed) <= 1e-10});
  }

  const double scale = profile.quick ? 1.0 : 10.0;
  for (const ObjectLight light : {ObjectLight::directional, ObjectLight::pole_beam}) {
    for (const Cell& c : cells) {
      // A sphere of 10 mfp keeps each photon for more events: fewer photons.
      const auto photons = static_cast<std::uint64_t>(scale * (c.radius > 1.0 ? 5e3 : 2e4));
      // Each cell its own photons.
      const std::uint64_t seed = profile.seed + section.table.rows.size();
      const TransportOutput out = run_lit_sphere(
          sphere_spec(c.albedo, c.g, c.eta, c.radius, light, report_run(photons, seed, profile)));
      section.non_finite_values += count_non_finite(out.tallies);
      const double n = static_cast<double>(photons);
      const std::string cell = fmt::format("{}, albedo {}, g {}, eta {}, R {} mfp",
                                           to_string(light), c.albedo, c.g, c.eta, c.radius);
      const auto [energy, orders] =
          energy_residuals(out, estimate(out, "reflected_at_entry").mean, {"exited", "absorbed"});
      section.checks.push_back(
          {fmt::format("{}: energy residual {:.2g}, by order {:.2g}, within 1e-12", cell, energy,
                       orders),
           std::abs(energy) <= 1e-12 && std::abs(orders) <= 1e-12});

      const Unscattered exact = exact_unscattered(light, c.eta, c.radius);
      const Estimate reflected = estimate(out, "reflected_at_entry");
      const bool reflected_ok = light == ObjectLight::pole_beam
                                    ? std::abs(reflected.mean - exact.reflected) <= 1e-12
                                    : agrees(reflected, exact.reflected, n);
      section.checks.push_back({fmt::format("{}: reflected at entry {:.6g} against exact {:.6g}",
                                            cell, reflected.mean, exact.reflected),
                                reflected_ok});
      const Estimate exited = estimate(out, "exited_unscattered");
      section.checks.push_back({fmt::format("{}: exited unscattered {:.6g} against exact {:.6g}",
                                            cell, exited.mean, exact.leaves),
                                agrees(exited, exact.leaves, n)});
      const Estimate absorbed = estimate(out, "absorbed_unscattered");
      const double absorbed_exact = (1.0 - c.albedo) * exact.collides;
      section.checks.push_back(
          {fmt::format("{}: absorbed at the first collision {:.6g} against exact {:.6g}", cell,
                       absorbed.mean, absorbed_exact),
           agrees(absorbed, absorbed_exact, n)});
      section.table.rows.push_back(
          {to_string(light), fmt::format("{}", c.albedo), fmt::format("{}", c.g),
           fmt::format("{}", c.eta), fmt::format("{}", c.radius), fmt::format("{}", photons),
           fmt::format("{:.3g}", out.wall_seconds), fmt::format("{:.2g}", energy),
           fmt::format("{:.2f}", z_score(reflected, exact.reflected)),
           fmt::format("{:.6g}", exited.mean), fmt::format("{:.6g}", exact.leaves),
           fmt::format("{:.2f}", z_score(exited, exact.leaves)),
           fmt::format("{:.2f}", z_score(absorbed, absorbed_exact))});
    }
  }
  section.findings = checks_over_cells(section);
  return section;
}

}  // namespace scatterlab::report
