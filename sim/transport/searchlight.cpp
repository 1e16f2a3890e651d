#include "scatterlab/transport/searchlight.hpp"

#include <fmt/format.h>

#include <cmath>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/tally/filter.hpp"
#include "scatterlab/transport/grid_checks.hpp"
#include "scatterlab/transport/length_units.hpp"

namespace scatterlab {
namespace {

std::string got(double value) {
  return fmt::format("got {}", value);
}

void check_grid(const HalfSpaceGrid& grid, const Medium& medium) {
  check_from_zero(grid.r, "r", "the distance from the entry point", "medium.length_unit");
  check_from_zero(grid.z, "z", "the surface", "medium.length_unit");
  check_length_axis_span(grid.r, "r", medium);
  check_length_axis_span(grid.z, "z", medium);
  if (grid.theta_o.min != 0.0 || std::abs(grid.theta_o.max - 0.5 * std::numbers::pi) > 1e-12) {
    throw InputError("grid.theta_o",
                     fmt::format("spans [{}, {}]", grid.theta_o.min, grid.theta_o.max),
                     "[0, pi/2]: exit angles from the outward normal");
  }
  check_bins(grid.theta_o, "theta_o");
}

void check_map(const HalfSpaceGrid& grid, const Medium& medium) {
  for (const auto& [axis, name] : {std::pair{&grid.x, "x"}, std::pair{&grid.y, "y"}}) {
    if (!(axis->min < axis->max)) {
      throw InputError(std::string("grid.") + name,
                       fmt::format("spans [{}, {}]", axis->min, axis->max),
                       "min < max (in medium.length_unit, about the entry point)");
    }
    check_length_axis_span(*axis, name, medium);
    check_bins(*axis, name);
  }
  if (static_cast<double>(grid.x.bins) * grid.y.bins > 1e7) {
    throw InputError("grid.y.bins", fmt::format("makes {} x {} bins", grid.x.bins, grid.y.bins),
                     "grid.x.bins x grid.y.bins at most 1e7");
  }
}

void check_run(const RunSettings& run, const Medium& medium) {
  check_run_settings(run);
  check_escape_radius_span(run.escape_radius, medium);
  const double albedo = medium.albedo;
  // With albedo 1 every photon leaves in the end (its depth is a recurrent 1-D walk), but the
  // number of events before it does has infinite mean, so a run would have no bounded cost.
  if (albedo == 1.0 && !std::isfinite(run.escape_radius)) {
    throw InputError("run.escape_radius",
                     "is infinite, but with albedo 1 the number of events per photon has no "
                     "finite mean; set run.escape_radius",
                     "a finite number > 0 (mfp) when medium.albedo = 1");
  }
  check_run_length(run, medium.albedo, run.escape_radius * mfp_per_length_unit(medium));
}

// The beam arrives in the x-z plane at `incidence_deg` from the inward normal +z.
Vec3 incident_direction(double incidence_deg) {
  const double theta = incidence_deg * std::numbers::pi / 180.0;
  return {std::sin(theta), 0.0, std::cos(theta)};
}

// The half-space's tallies, each declared once. Unscattered light only travels deeper: it never
// leaves a half-space, so the unscattered surface tallies are zero by construction; they are
// written so that every order sums.
std::vector<TallyDeclaration> declare_tallies(const HalfSpaceSpec& spec, double specular) {
  const HalfSpaceGrid& grid = spec.grid;
  const Filter r = radius_filter(grid.r);
  std::vector<TallyDeclaration> tallies;
  tallies.push_back({"reflectance",
                     Score::exitance,
                     {r},
                     Units{1, -2},
                     "diffuse reflectance R_d(r): power leaving the surface per unit area, ring "
                     "average",
                     true});
  tallies.push_back({"exitant_radiance",
                     Score::exitance,
                     {r, exit_angle_filter(grid.theta_o)},
                     Units{1, -2, -1},
                     "radiance leaving the surface outside the medium, L(r, theta_o) with theta_o "
                     "from the outward normal: power / (ring area x projected solid angle) of the "
                     "bin",
                     true});
  if (spec.tallies.fluence) {
    tallies.push_back({"fluence",
                       Score::fluence,
                       {r, depth_filter(grid.z)},
                       Units{1, -2},
                       "fluence phi(r, z) inside the medium, bin average, collision estimator",
                       true});
  }
  if (spec.tallies.exitance_map) {
    tallies.push_back(
        {"exitance_map",
         Score::exitance,
         {position_filter(Coordinate::x, grid.x), position_filter(Coordinate::y, grid.y)},
         Units{1, -2},
         "radiant exitance M(x, y) of the surface about the entry point: power "
         "leaving per unit area, cell average (the beam arrives in the x-z plane)",
         true});
  }
  tallies.push_back({"diffuse_reflectance",
                     Score::exitance,
                     {},
                     Units{},
                     "total power leaving the surface after scattering (all radii and angles)",
                     true});
  tallies.push_back({"specular_reflectance",
                     Score::exact,
                     {},
                     Units{},
                     "Fresnel reflection of the beam at entry (exact: no standard error)",
                     false,
                     specular});
  tallies.push_back(
      {"absorbed", Score::absorbed, {}, Units{}, "power absorbed anywhere in the medium"});
  if (std::isfinite(spec.run.escape_radius)) {
    tallies.push_back({"escaped",
                       Score::escaped,
                       {},
                       Units{},
                       "power carried past the escape radius (see /parameters escape_radius)"});
  }
  return tallies;
}

}  // namespace

void HalfSpaceSpec::validate() const {
  medium.validate();
  check_length_unit(medium);
  // Real interfaces stay well inside (water 1.33, diamond 2.42, germanium 4 in the infrared);
  // far outside, the Fresnel terms round to 0/0 and every tally to NaN (eta = 1e300).
  if (!(eta >= min_eta && eta <= max_eta)) {
    throw InputError("surface.eta", got(eta),
                     "a number in [0.1, 10] (n_medium / n_outside; 1 for no interface)");
  }
  if (!(incidence_deg >= 0.0 && incidence_deg < 90.0)) {
    throw InputError("source.incidence_deg", got(incidence_deg),
                     "an angle in [0, 90) degrees from the surface normal");
  }
  check_grid(grid, medium);
  if (tallies.exitance_map) check_map(grid, medium);
  check_run(run, medium);
  check_declared_tallies(declared_tallies, homogeneous_frame("half_space", medium, eta));
}

std::string fingerprint(const HalfSpaceSpec& spec) {
  auto axis = [](const UniformAxis& a) {
    return fmt::format("{:a},{:a},{};", a.min, a.max, a.bins);
  };
  const Medium& m = spec.medium;
  return fingerprint_of(fmt::format("half_space|medium {:a} {:a} {:a} {}|eta {:a}|incidence "
                                    "{:a}|grid {}{}{}|fluence {}|run {} "
                                    "{} {} {:a}",
                                    m.albedo, m.g, m.sigma_t, m.length_unit, spec.eta,
                                    spec.incidence_deg, axis(spec.grid.r), axis(spec.grid.z),
                                    axis(spec.grid.theta_o), spec.tallies.fluence, spec.run.photons,
                                    spec.run.batches, spec.run.seed, spec.run.escape_radius) +
                        (spec.tallies.exitance_map
                             ? fmt::format("|map {}{}", axis(spec.grid.x), axis(spec.grid.y))
                             : std::string()) +
                        fingerprint_text(spec.declared_tallies));
}

TransportProblem transport_problem(const HalfSpaceSpec& given) {
  // Lengths into mfp (length_units.hpp): r, z and the escape radius; "mfp" specs as they are.
  HalfSpaceSpec spec = given;
  if (given.medium.length_unit != "mfp") {
    const double mfp_per_unit = mfp_per_length_unit(given.medium);
    spec.grid.r = length_axis_in_mfp(given.grid.r, mfp_per_unit);
    spec.grid.z = length_axis_in_mfp(given.grid.z, mfp_per_unit);
    spec.grid.x = length_axis_in_mfp(given.grid.x, mfp_per_unit);
    spec.grid.y = length_axis_in_mfp(given.grid.y, mfp_per_unit);
    spec.run.escape_radius = given.run.escape_radius * mfp_per_unit;
  }
  // Entry (Bitterli §2.3): the specular part F(theta_i) is reflected, 1 - F enters along the
  // refracted ray. Beyond the critical angle of an eta < 1 medium nothing enters; the walk then
  // runs on the source's default direction, +z, and every tally is scaled by the transmitted power,
  // 0.
  const Vec3 incident = incident_direction(spec.incidence_deg);
  const double specular = fresnel_dielectric_terms(incident.z(), spec.eta).reflectance();
  TransportProblem problem;
  problem.albedo = spec.medium.albedo;
  problem.g = spec.medium.g;
  problem.geometry = GeometryKind::half_space;
  problem.eta = spec.eta;
  refract(incident, -Vec3::UnitZ(), spec.eta, problem.source.direction);
  problem.axes.r = spec.grid.r;
  problem.axes.z = spec.grid.z;
  problem.axes.theta_o = spec.grid.theta_o;
  if (spec.tallies.exitance_map) {
    problem.axes.x = spec.grid.x;
    problem.axes.y = spec.grid.y;
  }
  problem.tallies = declare_tallies(spec, specular);
  for (TallyDeclaration& d : declare_chained_tallies(
           spec.declared_tallies, homogeneous_frame("half_space", spec.medium, spec.eta),
           problem.tallies)) {
    problem.tallies.push_back(std::move(d));
  }
  problem.split_by_order = true;
  problem.estimator = Estimator::collision;
  problem.photon_power = 1.0 - specular;
  problem.run = spec.run;
  problem.length = reported_length(spec.medium);  // back from mfp
  problem.size_fields = spec.tallies.fluence
                            ? "grid.r.bins x grid.z.bins (fluence), grid.theta_o.bins, run.threads"
                            : "grid.r.bins x grid.theta_o.bins, run.threads";
  return problem;
}

TransportOutput run_half_space(const HalfSpaceSpec& spec, const ProgressCallback& progress,
                               const RunControl& control) {
  spec.validate();
  return transport(transport_problem(spec), progress, control);
}

}  // namespace scatterlab
