// The layered slab's Monte Carlo (transport/layered_slab.hpp) against exact and published values:
//  - error against run time: van de Hulst's slab of optical thickness 2, albedo 0.9, g 0.75,
//    index-matched, as MCML's paper quotes it (Wang, Jacques & Zheng 1995, Table 2):
//    R_d = 0.09739, T_t = 0.66096 (five digits: rounding 5e-6);
//  - Giovanelli's semi-infinite medium, isotropic, albedo 0.9, behind an n = 1.5 surface: the
//    whole surface's reflectance R_sp + R_d = 0.2600 (Giovanelli 1955, as the MCML manual quotes
//    it, Wang & Jacques 1992, §6.1, Table 6.2; four digits: rounding 5e-5);
//  - stiff and extreme cases over albedo, g, n and thickness: energy photon by photon, the
//    specular reflection, and the unscattered light exactly. A layer of optical depth tau and
//    index n between media of index 1 reflects r = F(1) at each face; light that entered crosses
//    it with E = e^-tau, and at each face leaves with 1 - r or turns back, so per unit power
//    incident (MCML's R_sp = r aside):
//      transmitted unscattered   (1 - r)^2 E / (1 - r^2 E^2),
//      reflected unscattered     (1 - r)^2 r E^2 / (1 - r^2 E^2),
//      collides                  (1 - r) (1 - E) / (1 - r E),
//    and the first collision absorbs a share 1 - albedo of what collides.

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>
#include <vector>

#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/report/suites.hpp"
#include "scatterlab/transport/layered_slab.hpp"
#include "simulation_checks.hpp"

namespace scatterlab::report {
namespace {

constexpr double kMuT = 10.0;  // 1 / cm: thicknesses are optical depths / 10 cm

// One analog layer of optical depth `tau` (infinite: semi-infinite), index n, in air.
LayeredSlabSpec one_layer(double albedo, double g, double n, double tau, const RunSettings& run) {
  LayeredSlabSpec spec;
  spec.layers = {
      SlabLayerSpec{kMuT * (1.0 - albedo), kMuT * albedo, g, n, tau / kMuT, std::nullopt}};
  spec.r = UniformAxis{0.0, 0.5, 10};
  spec.z = UniformAxis{0.0, 0.4, 10};
  spec.theta_o = UniformAxis{0.0, std::numbers::pi / 2.0, 6};
  spec.run = run;
  return spec;
}

struct Unscattered {
  double transmitted, reflected, collides;
};

Unscattered exact_unscattered(double n, double tau) {
  const double r = fresnel_dielectric_reflectance(1.0, n);
  const double e = std::exp(-tau);  // 0 for a semi-infinite layer
  const double bounces = 1.0 - r * r * e * e;
  return {(1.0 - r) * (1.0 - r) * e / bounces, (1.0 - r) * (1.0 - r) * r * e * e / bounces,
          (1.0 - r) * (1.0 - e) / (1.0 - r * e)};
}

}  // namespace

Section slab_convergence(const Profile& profile) {
  Section section;
  section.id = "slab_convergence";
  section.title = "Layered slab: error against run time";
  section.reference =
      "van de Hulst's slab: optical thickness 2, albedo 0.9, g 0.75, index-matched, under a "
      "normal beam: diffuse reflectance R_d = 0.09739 and total transmittance T_t = 0.66096 "
      "(the unscattered light included), as MCML's paper quotes the table (Wang, Jacques & "
      "Zheng 1995, Table 2).";
  section.tolerance =
      "Each budget within 5 standard errors plus the table's rounding (5e-6) of each value; the "
      "standard error falls as N^-1/2 (least-squares slope of log stderr against log photons in "
      "[-0.6, -0.4]).";
  add_error_against_run_time(
      section, profile,
      {{"diffuse_reflectance", "$R_\\mathrm{d}$", 0.09739, 5e-6},
       {"total_transmittance", "$T_\\mathrm{t}$", 0.66096, 5e-6}},
      "van de Hulst's slab, optical thickness 2, albedo 0.9, g 0.75",
      [&](std::uint64_t photons, std::uint64_t seed) {
        return run_layered_slab(one_layer(0.9, 0.75, 1.0, 2.0, report_run(photons, seed, profile)));
      });
  return section;
}

Section slab_extremes(const Profile& profile) {
  Section section;
  section.id = "slab_extremes";
  section.title = "Layered slab: stiff and extreme cases";
  section.reference =
      "Energy photon by photon (R_sp + R_d + T_t + A = 1, and each by scattering order); the "
      "specular reflection against Fresnel's at normal incidence; the unscattered light "
      "transmitted, reflected and absorbed at the first collision against its closed form (a "
      "geometric series of reflections between the faces); Giovanelli's semi-infinite medium "
      "behind n = 1.5, R_sp + R_d = 0.2600.";
  section.tolerance =
      "Energy to 1e-12; specular to 1e-15 (it is deterministic); each unscattered part within "
      "5 standard errors, or, where no photon was scored, an exact value below 3 / photons; "
      "Giovanelli's within 5 standard errors plus its rounding (5e-5). No NaN or Inf.";
  section.table.columns = {"albedo",
                           "g",
                           "n",
                           "tau",
                           "photons",
                           "seconds",
                           "energy_residual",
                           "specular",
                           "transmitted_unscattered",
                           "transmitted_exact",
                           "transmitted_z",
                           "reflected_z",
                           "absorbed_z"};
  struct Cell {
    double albedo, g, n, tau;
  };
  constexpr double semi_infinite = std::numeric_limits<double>::infinity();
  std::vector<Cell> cells;
  for (double albedo : {1e-6, 0.5, 1.0 - 1e-6}) {
    for (double g : {-0.999, 0.0, 0.999}) cells.push_back({albedo, g, 1.4, 1.0});
  }
  for (double n : {1.0, 1.0001, 2.5}) cells.push_back({0.9, 0.5, n, 1.0});
  for (double tau : {1e-3, 10.0, semi_infinite}) cells.push_back({0.9, 0.5, 1.4, tau});

  const double scale = profile.quick ? 1.0 : 10.0;
  for (const Cell& c : cells) {
    const auto photons = static_cast<std::uint64_t>(scale * 2e4);
    const std::uint64_t seed = profile.seed + section.table.rows.size();  // each cell its own
    const TransportOutput out =
        run_layered_slab(one_layer(c.albedo, c.g, c.n, c.tau, report_run(photons, seed, profile)));
    section.non_finite_values += count_non_finite(out.tallies);
    const double count = static_cast<double>(photons);
    const std::string cell =
        fmt::format("albedo {}, g {}, n {}, tau {}", c.albedo, c.g, c.n, c.tau);
    const double specular = estimate(out, "specular_reflectance").mean;
    const auto [energy, orders] =
        energy_residuals(out, specular, {"diffuse_reflectance", "total_transmittance", "absorbed"});
    section.checks.push_back({fmt::format("{}: energy residual {:.2g}, by order {:.2g}, within "
                                          "1e-12",
                                          cell, energy, orders),
                              std::abs(energy) <= 1e-12 && std::abs(orders) <= 1e-12});
    const double specular_exact = fresnel_dielectric_reflectance(1.0, c.n);
    section.checks.push_back({fmt::format("{}: specular {:.12f} against Fresnel {:.12f}", cell,
                                          specular, specular_exact),
                              std::abs(specular - specular_exact) <= 1e-15});

    const Unscattered exact = exact_unscattered(c.n, c.tau);
    const Estimate transmitted = estimate(out, "total_transmittance_unscattered");
    const Estimate reflected = estimate(out, "diffuse_reflectance_unscattered");
    const Estimate absorbed = estimate(out, "absorbed_unscattered");
    const double absorbed_exact = (1.0 - c.albedo) * exact.collides;
    for (const auto& [what, e, x] :
         {std::tuple{"transmitted", transmitted, exact.transmitted},
          std::tuple{"reflected", reflected, exact.reflected},
          std::tuple{"absorbed at the first collision", absorbed, absorbed_exact}}) {
      section.checks.push_back(
          {fmt::format("{}: unscattered {} {:.6g} against exact {:.6g}", cell, what, e.mean, x),
           agrees(e, x, count)});
    }
    section.table.rows.push_back(
        {fmt::format("{}", c.albedo), fmt::format("{}", c.g), fmt::format("{}", c.n),
         fmt::format("{}", c.tau), fmt::format("{}", photons),
         fmt::format("{:.3g}", out.wall_seconds), fmt::format("{:.2g}", energy),
         fmt::format("{:.9f}", specular), fmt::format("{:.6g}", transmitted.mean),
         fmt::format("{:.6g}", exact.transmitted),
         fmt::format("{:.2f}", z_score(transmitted, exact.transmitted)),
         fmt::format("{:.2f}", z_score(reflected, exact.reflected)),
         fmt::format("{:.2f}", z_score(absorbed, absorbed_exact))});
  }

  // Giovanelli's medium: mu_a 10, mu_s 90 per cm, isotropic, semi-infinite, behind n = 1.5.
  const auto photons = static_cast<std::uint64_t>(scale * 1e5);
  const TransportOutput out = run_layered_slab(
      one_layer(0.9, 0.0, 1.5, semi_infinite, report_run(photons, profile.seed, profile)));
  section.non_finite_values += count_non_finite(out.tallies);
  const Estimate diffuse = estimate(out, "diffuse_reflectance");
  const double surface = estimate(out, "specular_reflectance").mean + diffuse.mean;
  section.checks.push_back(
      {fmt::format("Giovanelli's semi-infinite medium: R_sp + R_d {:.5f} +- {:.5f} against "
                   "0.2600",
                   surface, diffuse.stderr_of_mean),
       std::abs(surface - 0.2600) <= 5.0 * diffuse.stderr_of_mean + 5e-5});
  section.findings = fmt::format(
      "{} of {} checks pass over {} cells. Giovanelli's medium: R_sp + R_d = {:.5f} +- {:.5f} "
      "({} photons) against 0.2600.\n",
      section.checks_passed(), section.checks.size(), section.table.rows.size(), surface,
      diffuse.stderr_of_mean, photons);
  return section;
}

}  // namespace scatterlab::report
