// Stiff and extreme cases of the infinite-medium simulator: albedo -> 0 and -> 1, g -> 0 from
// both sides and |g| -> 1. Each cell is checked against identities that hold exactly for a
// pencil beam in an infinite medium with analog absorption:
//   energy:   absorbed inside + outside the grid = 1 (nothing escapes an infinite medium);
//   depth:    <z_abs> = sum_n (albedo g)^n = 1 / (1 - albedo g), since flight n has mean length
//             1 mfp, mean direction cosine g^n, and is flown with probability albedo^n;
//   events:   the number of scatterings is geometric, with mean albedo / (1 - albedo) and
//             standard deviation sqrt(albedo) / (1 - albedo).

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "scatterlab/report/suites.hpp"
#include "simulation_checks.hpp"

namespace scatterlab::report {

Section infinite_medium_extremes(const Profile& profile) {
  Section section;
  section.id = "infinite_medium_extremes";
  section.title = "Infinite medium: stiff and extreme cases";
  section.reference =
      "Identities exact for a pencil beam in an infinite medium with analog absorption: energy "
      "balance (absorbed = 1), the mean absorption depth 1 / (1 - albedo g), and the mean "
      "number of scattering events per photon albedo / (1 - albedo).";
  section.tolerance =
      "Energy to 1e-12 (each photon deposits exactly 1). Depth and events within 5 standard "
      "errors (the batch standard error of the depth tally; sqrt(albedo) / ((1 - albedo) "
      "sqrt(N)) for the event count). No NaN or Inf anywhere.";
  section.table.columns = {"albedo",      "g",          "photons",       "seconds",
                           "energy_residual", "depth",  "depth_exact",   "depth_z",
                           "events",      "events_exact", "events_z",    "non_finite"};

  const double scale = profile.quick ? 1.0 : 10.0;
  for (double albedo : {0.0, 1e-6, 0.5, 0.99, 0.9999}) {
    for (double g : {-0.999, -1e-9, 0.0, 1e-9, 0.9, 0.999}) {
      InfiniteMediumSpec spec;
      spec.medium.albedo = albedo;
      spec.medium.g = g;
      spec.tallies.radiance = false;
      spec.tallies.flux = false;
      // About 2e7 scattering events at high albedo, 2e5 photons at low albedo.
      spec.run.photons =
          static_cast<std::uint64_t>(scale * std::clamp(2e6 * (1.0 - albedo), 2e3, 2e5));
      spec.run.batches = 32;
      spec.run.seed = profile.seed;
      spec.run.threads = profile.threads;
      const TransportOutput out = run_infinite_medium(spec);
      const int non_finite = count_non_finite(out.tallies);
      section.non_finite_values += non_finite;

      const double n = static_cast<double>(spec.run.photons);
      const double energy = tally(out.tallies, "absorbed").mean[0] +
                            tally(out.tallies, "absorbed_outside_grid").mean[0] - 1.0;
      const TallyResult& depth = tally(out.tallies, "absorbed_mean_depth");
      const double depth_exact = 1.0 / (1.0 - albedo * g);
      const double depth_z = (depth.mean[0] - depth_exact) / depth.stderr_of_mean[0];
      const double events = static_cast<double>(out.scattering_events) / n;
      const double events_exact = albedo / (1.0 - albedo);
      const double events_sigma = std::sqrt(albedo) / (1.0 - albedo) / std::sqrt(n);
      const double events_z = albedo == 0.0 ? 0.0 : (events - events_exact) / events_sigma;

      const std::string cell = fmt::format("albedo {}, g {}", albedo, g);
      section.checks.push_back({fmt::format("{}: energy residual {:.3g} within 1e-12", cell,
                                            energy),
                                std::abs(energy) <= 1e-12});
      section.checks.push_back(
          {fmt::format("{}: absorption depth z-score {:.2f} within 5", cell, depth_z),
           std::abs(depth_z) <= 5.0});
      section.checks.push_back(
          {fmt::format("{}: scattering events z-score {:.2f} within 5", cell, events_z),
           std::abs(events_z) <= 5.0});
      section.table.rows.push_back(
          {fmt::format("{}", albedo), fmt::format("{}", g), fmt::format("{}", spec.run.photons),
           fmt::format("{:.3g}", out.wall_seconds), fmt::format("{:.3g}", energy),
           fmt::format("{:.6g}", depth.mean[0]), fmt::format("{:.6g}", depth_exact),
           fmt::format("{:.2f}", depth_z), fmt::format("{:.6g}", events),
           fmt::format("{:.6g}", events_exact), fmt::format("{:.2f}", events_z),
           fmt::format("{}", non_finite)});
    }
  }
  section.findings = checks_over_cells(section);
  return section;
}

}  // namespace scatterlab::report
