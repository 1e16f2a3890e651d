#include "scatterlab/transport/searchlight.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/phase_function.hpp"
#include "scatterlab/tally/half_space_layout.hpp"
#include "scatterlab/tally/half_space_scorer.hpp"
#include "scatterlab/transport/half_space_walk.hpp"

namespace scatterlab {
namespace {

constexpr int max_bins = 100'000;

std::string got(double value) {
  return fmt::format("got {}", value);
}

void check_bins(const UniformAxis& axis, const std::string& name) {
  if (axis.bins < 1 || axis.bins > max_bins) {
    throw InputError("grid." + name + ".bins", fmt::format("got {}", axis.bins),
                     "an integer in [1, 100000]");
  }
}

// r and z both start at the entry point: r = 0 on the beam, z = 0 on the surface.
void check_from_zero(const UniformAxis& axis, const std::string& name, const char* what) {
  if (axis.min != 0.0) {
    throw InputError("grid." + name + ".min", got(axis.min), std::string("0 (") + what + ")");
  }
  if (!(axis.max > 0.0) || !std::isfinite(axis.max)) {
    throw InputError("grid." + name + ".max", got(axis.max), "a finite number > 0 (mfp)");
  }
  check_bins(axis, name);
}

void check_grid(const SearchlightGrid& grid) {
  check_from_zero(grid.r, "r", "the distance from the entry point");
  check_from_zero(grid.z, "z", "the surface");
  if (grid.theta_o.min != 0.0 || std::abs(grid.theta_o.max - 0.5 * std::numbers::pi) > 1e-12) {
    throw InputError("grid.theta_o",
                     fmt::format("spans [{}, {}]", grid.theta_o.min, grid.theta_o.max),
                     "[0, pi/2]: exit angles from the outward normal");
  }
  check_bins(grid.theta_o, "theta_o");
}

void check_run(const RunSettings& run, double albedo) {
  check_run_settings(run);
  // With albedo 1 every photon leaves in the end (its depth is a recurrent 1-D walk), but the
  // number of events before it does has infinite mean, so a run would have no bounded cost.
  if (albedo == 1.0 && !std::isfinite(run.escape_radius)) {
    throw InputError("run.escape_radius",
                     "is infinite, but with albedo 1 the number of events per photon has no "
                     "finite mean; set run.escape_radius",
                     "a finite number > 0 (mfp) when medium.albedo = 1");
  }
}

// The beam arrives in the x-z plane at `incidence_deg` from the inward normal +z.
Vec3 incident_direction(double incidence_deg) {
  const double theta = incidence_deg * std::numbers::pi / 180.0;
  return {std::sin(theta), 0.0, std::cos(theta)};
}

template <class Phase, bool fresnel, bool fluence>
SearchlightOutput run_kernel(const SearchlightSpec& spec, const Phase& phase,
                             const Vec3& entry_direction, const EntryPower& entry,
                             const ProgressCallback& progress, const RunControl& control) {
  const HalfSpaceLayout layout(spec);
  const HalfSpaceScorer scorer(spec, layout);
  const HalfSpaceWalk<Phase, fresnel, fluence> walk(spec, phase, scorer, entry_direction);
  const BatchOutcome outcome = run_batches(spec.run, layout.size, walk, progress, control);
  SearchlightOutput output;
  if (!outcome.mean.empty()) {  // the root's; other ranks fold only their slice
    output.tallies =
        finalize_half_space_tallies(spec, layout, entry, outcome.mean, outcome.standard_error);
  }
  output.photons = outcome.photons_done;
  output.batches_done = outcome.batches_done;
  output.ranks = outcome.ranks;
  output.threads = outcome.threads;
  output.scattering_events = outcome.scattering_events;
  return output;
}

// Picks the one specialised kernel the scene needs: fresnel x fluence for a given phase.
template <class Phase>
SearchlightOutput run_with(const SearchlightSpec& spec, const Phase& phase,
                           const Vec3& entry_direction, const EntryPower& entry,
                           const ProgressCallback& progress, const RunControl& control) {
  const bool fresnel = spec.eta != 1.0;
  const bool fluence = spec.tallies.fluence;
  if (fresnel && fluence)
    return run_kernel<Phase, true, true>(spec, phase, entry_direction, entry, progress, control);
  if (fresnel) return run_kernel<Phase, true, false>(spec, phase, entry_direction, entry, progress, control);
  if (fluence) return run_kernel<Phase, false, true>(spec, phase, entry_direction, entry, progress, control);
  return run_kernel<Phase, false, false>(spec, phase, entry_direction, entry, progress, control);
}

}  // namespace

void SearchlightSpec::validate() const {
  medium.validate();
  if (medium.sigma_t != 1.0 || medium.length_unit != "mfp") {
    throw InputError("medium.sigma_t", got(medium.sigma_t),
                     "1: the searchlight runs in mean free paths");
  }
  if (!(eta > 0.0) || !std::isfinite(eta)) {
    throw InputError("surface.eta", got(eta),
                     "a finite number > 0 (n_medium / n_outside; 1 for no interface)");
  }
  if (!(incidence_deg >= 0.0 && incidence_deg < 90.0)) {
    throw InputError("source.incidence_deg", got(incidence_deg),
                     "an angle in [0, 90) degrees from the surface normal");
  }
  check_grid(grid);
  check_run(run, medium.albedo);
}

std::string fingerprint(const SearchlightSpec& spec) {
  auto axis = [](const UniformAxis& a) { return fmt::format("{:a},{:a},{};", a.min, a.max, a.bins); };
  const Medium& m = spec.medium;
  return fingerprint_of(fmt::format(
      "half_space|medium {:a} {:a} {:a} {}|eta {:a}|incidence {:a}|grid {}{}{}|fluence {}|run {} "
      "{} {} {:a}",
      m.albedo, m.g, m.sigma_t, m.length_unit, spec.eta, spec.incidence_deg, axis(spec.grid.r),
      axis(spec.grid.z), axis(spec.grid.theta_o), spec.tallies.fluence, spec.run.photons,
      spec.run.batches, spec.run.seed, spec.run.escape_radius));
}

SearchlightOutput run_searchlight(const SearchlightSpec& spec, const ProgressCallback& progress,
                                  const RunControl& control) {
  spec.validate();
  const auto start = std::chrono::steady_clock::now();

  // Entry (Bitterli §2.3): the specular part F(theta_i) is reflected, 1 - F enters along the
  // refracted ray. Beyond the critical angle of an eta < 1 medium nothing enters; the walk then
  // runs on a dummy direction and every tally is scaled by the transmitted power, 0.
  const Vec3 incident = incident_direction(spec.incidence_deg);
  const FresnelDielectric at_entry = fresnel_dielectric_terms(incident.z(), spec.eta);
  const EntryPower entry{at_entry.reflectance(), 1.0 - at_entry.reflectance()};
  Vec3 entry_direction = Vec3::UnitZ();
  refract(incident, -Vec3::UnitZ(), spec.eta, entry_direction);

  // g = 0 samples isotropically: no HG arithmetic where the scene does not need it.
  SearchlightOutput output =
      spec.medium.g == 0.0
          ? run_with(spec, IsotropicPhase{}, entry_direction, entry, progress, control)
          : run_with(spec, HenyeyGreenstein{spec.medium.g}, entry_direction, entry, progress, control);
  output.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return output;
}

}  // namespace scatterlab
