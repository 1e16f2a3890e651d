// The half-space (searchlight) Monte Carlo against exact references:
//  - error against run time: index-matched, isotropic scattering, whose total diffuse
//    reflectance under a normal beam is 1 - H(1) sqrt(1 - albedo) (Chandrasekhar's H-function,
//    models/chandrasekhar_h.hpp);
//  - stiff and extreme cases over albedo, g, eta and the beam's incidence: energy balance, the
//    specular part against the Fresnel reflectance, and the once-scattered reflectance against
//    the exact refractive single-scatter solution (refract/half_space_single_scatter.hpp).

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/models/chandrasekhar_h.hpp"
#include "scatterlab/refract/half_space_single_scatter.hpp"
#include "scatterlab/report/suites.hpp"
#include "scatterlab/transport/searchlight.hpp"
#include "simulation_checks.hpp"

namespace scatterlab::report {
namespace {

HalfSpaceSpec small_spec(double albedo, double g, double eta, const RunSettings& run) {
  HalfSpaceSpec spec;
  spec.medium.albedo = albedo;
  spec.medium.g = g;
  spec.eta = eta;
  spec.grid.r = UniformAxis{0.0, 10.0, 40};
  spec.tallies.fluence = false;
  spec.run = run;
  return spec;
}

}  // namespace

Section half_space_convergence(const Profile& profile) {
  Section section;
  section.id = "half_space_convergence";
  section.title = "Half-space: error against run time";
  constexpr double albedo = 0.9;
  const double exact = half_space_diffuse_reflectance(albedo);
  section.reference = fmt::format(
      "Total diffuse reflectance of an index-matched half-space with isotropic scattering, "
      "albedo {}, under a normal pencil beam: 1 - H(1) sqrt(1 - albedo) = {:.9f} "
      "(Chandrasekhar's H-function).",
      albedo, exact);
  section.tolerance =
      "Each budget within 5 standard errors of the exact value; the standard error falls as "
      "N^-1/2 (least-squares slope of log stderr against log photons in [-0.6, -0.4]).";
  add_error_against_run_time(
      section, profile, {{"diffuse_reflectance", "$R_\\mathrm{d}$", exact}},
      fmt::format("Index-matched half-space, normal beam, albedo {:g}", albedo),
      [&](std::uint64_t photons, std::uint64_t seed) {
        return run_half_space(small_spec(albedo, 0.0, 1.0, report_run(photons, seed, profile)));
      });
  return section;
}

Section half_space_extremes(const Profile& profile) {
  Section section;
  section.id = "half_space_extremes";
  section.title = "Half-space: stiff and extreme cases";
  section.reference =
      "Energy balance (specular + diffuse + absorbed = 1); the specular part against the exact "
      "dielectric Fresnel reflectance at the beam's incidence; the once-scattered total "
      "reflectance against the exact refractive single-scatter solution (normal incidence).";
  section.tolerance =
      "Energy to 1e-12; specular to 1e-12 (it is deterministic); once-scattered total within "
      "5 standard errors, or, where no photon left after exactly one scattering, an exact "
      "value below 3 / photons. No NaN or Inf.";
  section.table.columns = {"albedo",  "g",           "eta",         "incidence_deg", "photons",
                           "seconds", "energy_residual", "specular", "specular_exact",
                           "single",  "single_exact", "single_z"};
  struct Cell {
    double albedo, g, eta, incidence;
  };
  std::vector<Cell> cells;
  for (double albedo : {0.0, 1e-6, 0.5, 0.99, 0.9999}) {
    for (double g : {-0.999, -1e-9, 0.0, 1e-9, 0.9, 0.999}) cells.push_back({albedo, g, 1.33, 0.0});
  }
  for (double eta : {1.0, 1.0001, 2.5, 0.75}) cells.push_back({0.9, 0.5, eta, 0.0});
  cells.push_back({0.9, 0.5, 1.33, 89.0});  // grazing
  cells.push_back({0.9, 0.5, 0.75, 60.0});  // beyond the critical angle: nothing enters

  const double scale = profile.quick ? 1.0 : 10.0;
  for (const Cell& c : cells) {
    const auto photons = static_cast<std::uint64_t>(scale * (c.albedo > 0.99 ? 5e3 : 2e4));
    HalfSpaceSpec spec =
        small_spec(c.albedo, c.g, c.eta, report_run(photons, profile.seed, profile));
    spec.incidence_deg = c.incidence;
    const TransportOutput out = run_half_space(spec);
    section.non_finite_values += count_non_finite(out.tallies);
    const double specular = estimate(out, "specular_reflectance").mean;
    const double energy =
        specular + estimate(out, "diffuse_reflectance").mean + estimate(out, "absorbed").mean - 1.0;
    // Outside to inside: index eta relative to outside.
    const double specular_exact =
        fresnel_dielectric_reflectance(std::cos(c.incidence * std::numbers::pi / 180.0), c.eta);
    const std::string cell = fmt::format("albedo {}, g {}, eta {}, incidence {}", c.albedo, c.g,
                                         c.eta, c.incidence);
    section.checks.push_back({fmt::format("{}: energy residual {:.2g} within 1e-12", cell, energy),
                              std::abs(energy) <= 1e-12});
    section.checks.push_back(
        {fmt::format("{}: specular {:.9f} against Fresnel {:.9f}", cell, specular, specular_exact),
         std::abs(specular - specular_exact) <= 1e-12});
    std::string single_text = "", exact_text = "", z_text = "";
    if (c.incidence == 0.0) {
      const std::vector<double> edges = {0.0, 1e3};
      const double exact =
          half_space_single_scatter_reflectance(spec.medium, c.eta, edges, 1e-9).total;
      const Estimate single = estimate(out, "diffuse_reflectance_single");
      const bool ok = agrees(single, exact, static_cast<double>(photons));
      const double z = z_score(single, exact);
      section.checks.push_back(
          {fmt::format("{}: once-scattered {:.6g} against exact {:.6g} (z {:.2f})", cell,
                       single.mean, exact, z),
           ok});
      single_text = fmt::format("{:.6g}", single.mean);
      exact_text = fmt::format("{:.6g}", exact);
      z_text = fmt::format("{:.2f}", z);
    }
    section.table.rows.push_back(
        {fmt::format("{}", c.albedo), fmt::format("{}", c.g), fmt::format("{}", c.eta),
         fmt::format("{}", c.incidence), fmt::format("{}", photons),
         fmt::format("{:.3g}", out.wall_seconds), fmt::format("{:.2g}", energy),
         fmt::format("{:.9f}", specular), fmt::format("{:.9f}", specular_exact), single_text,
         exact_text, z_text});
  }
  section.findings = checks_over_cells(section);
  return section;
}

}  // namespace scatterlab::report
