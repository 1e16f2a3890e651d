// Error against run time of the infinite-medium simulator: an isotropic point source in a
// medium that scatters isotropically, whose fluence is known exactly (point_source_exact.hpp).
// Monte Carlo error should fall as 1/sqrt(photons), i.e. 1/sqrt(seconds) once start-up costs
// are amortised.

#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "scatterlab/models/point_source_exact.hpp"
#include "scatterlab/report/suites.hpp"
#include "simulation_checks.hpp"

namespace scatterlab::report {
namespace {

constexpr double kAlbedo = 0.9;
constexpr double kRhoMin = 0.2, kRhoMax = 4.0;  // away from the 1/rho^2 core and the thin tail

struct Accuracy {
  double relative_rms_error;      // sqrt(mean(((mc - exact) / exact)^2)) over shells
  double predicted_relative_rms;  // the same with the batch standard errors in place of errors
  double mean_squared_z;          // mean of ((mc - exact) / stderr)^2
};

Accuracy accuracy(const TallyResult& fluence, const UniformAxis& shells,
                  const std::vector<double>& exact) {
  double error2 = 0.0, predicted2 = 0.0, z2 = 0.0;
  int used = 0;
  for (int i = 0; i < shells.bins; ++i) {
    if (shells.edge(i) < kRhoMin || shells.edge(i + 1) > kRhoMax) continue;
    const auto k = static_cast<std::size_t>(i);
    const double relative = (fluence.mean[k] - exact[k]) / exact[k];
    error2 += relative * relative;
    predicted2 += std::pow(fluence.stderr_of_mean[k] / exact[k], 2);
    z2 += std::pow((fluence.mean[k] - exact[k]) / fluence.stderr_of_mean[k], 2);
    ++used;
  }
  return {std::sqrt(error2 / used), std::sqrt(predicted2 / used), z2 / used};
}

}  // namespace

Section infinite_medium_convergence(const Profile& profile) {
  Section section;
  section.id = "infinite_medium_convergence";
  section.title = "Infinite medium: error against run time";
  section.reference = fmt::format(
      "Exact fluence of an isotropic point source in an infinite medium with isotropic "
      "scattering, albedo {} (discrete mode plus branch-cut integral, "
      "models/point_source_exact.hpp), averaged over the same spherical shells as the tally "
      "(0.1 mfp wide, rho in [{}, {}] mfp).",
      kAlbedo, kRhoMin, kRhoMax);
  section.tolerance =
      "The error must fall as N^-1/2: the least-squares slope of log(error) against "
      "log(photons) must lie in [-0.7, -0.3]. At the largest budget the mean squared z-score "
      "(error over batch standard error) must lie in [0.5, 2] for the collision estimator, whose "
      "shells are nearly independent, and below 4 for the track-length estimator, whose flights "
      "score runs of neighbouring shells with correlated errors.";
  section.table.columns = {"estimator",          "photons",         "seconds",
                           "events_per_second", "relative_rms_error", "predicted_relative_rms",
                           "mean_squared_z"};

  const UniformAxis shells{0.0, 5.0, 50};
  std::vector<double> exact(static_cast<std::size_t>(shells.bins));
  for (int i = 0; i < shells.bins; ++i) {
    exact[static_cast<std::size_t>(i)] =
        point_source_fluence_shell_average(kAlbedo, shells.edge(i), shells.edge(i + 1));
  }

  LinePlot plot{fmt::format("Infinite medium, isotropic point source, albedo {:g}:\nerror of the "
                            "fluence (shells {:g} to {:g} mfp) against photons\n(labels: wall time)",
                            kAlbedo, kRhoMin, kRhoMax),
                "photons",
                "relative RMS error of $\\phi$",
                AxisScale::log,
                true,
                {}};
  const int budgets = profile.quick ? 6 : 8;
  const double first_budget = profile.quick ? 2e4 : 1e5;
  for (Estimator estimator : {Estimator::collision, Estimator::track_length}) {
    std::vector<double> photons, seconds, errors;
    Accuracy last{};
    for (int b = 0; b < budgets; ++b) {
      InfiniteMediumSpec spec;
      spec.set_source(SourceKind::point);
      spec.medium.albedo = kAlbedo;
      spec.medium.g = 0.0;
      spec.tallies = TallyRequest{false, false, false, true, false, estimator};
      spec.grid.rho = shells;
      spec.run.photons = static_cast<std::uint64_t>(first_budget * std::ldexp(1.0, b));
      spec.run.batches = 32;
      spec.run.seed = profile.seed + static_cast<std::uint64_t>(b);
      spec.run.threads = profile.threads;
      const TransportOutput out = run_infinite_medium(spec);
      section.non_finite_values += count_non_finite(out.tallies);
      last = accuracy(tally(out.tallies, "fluence_spherical"), shells, exact);
      photons.push_back(static_cast<double>(spec.run.photons));
      seconds.push_back(out.wall_seconds);
      errors.push_back(last.relative_rms_error);
      section.table.rows.push_back(
          {to_string(estimator), fmt::format("{}", spec.run.photons),
           fmt::format("{:.4g}", out.wall_seconds),
           fmt::format("{:.4g}", static_cast<double>(out.scattering_events) / out.wall_seconds),
           fmt::format("{:.4g}", last.relative_rms_error),
           fmt::format("{:.4g}", last.predicted_relative_rms),
           fmt::format("{:.3f}", last.mean_squared_z)});
    }
    plot.series.push_back(
        {estimator == Estimator::collision ? "collision estimator" : "track-length estimator",
         photons,
         errors,
         {},
         true,
         to_string(estimator),
         wall_time_labels(seconds)});
    const double slope = log_log_slope(photons, errors);
    const double time_slope = log_log_slope(seconds, errors);
    section.checks.push_back(
        {fmt::format("{}: slope of log error against log photons {:.3f} in [-0.7, -0.3]",
                     to_string(estimator), slope),
         slope >= -0.7 && slope <= -0.3});
    const bool collision = estimator == Estimator::collision;
    section.checks.push_back(
        {fmt::format("{}: mean squared z-score {:.3f} at {} photons {}", to_string(estimator),
                     last.mean_squared_z, photons.back(), collision ? "in [0.5, 2]" : "below 4"),
         collision ? last.mean_squared_z >= 0.5 && last.mean_squared_z <= 2.0
                   : last.mean_squared_z < 4.0});
    section.findings += fmt::format(
        "- {}: relative RMS error {:.3g} at {:.3g} s ({:.0f} photons); slope of log error "
        "against log photons {:.3f}, against log seconds {:.3f} (1/sqrt law: -0.5).\n",
        to_string(estimator), errors.back(), seconds.back(), photons.back(), slope, time_slope);
  }
  // N^-1/2 through the collision estimator's first point: where the error should fall.
  PlotSeries ideal{"$\\propto N^{-1/2}$", {}, {}, {}, false, "straight"};
  const PlotSeries& first = plot.series.front();
  for (const double n : first.x) {
    ideal.x.push_back(n);
    ideal.y.push_back(first.y.front() * std::sqrt(first.x.front() / n));
  }
  plot.series.push_back(ideal);
  section.figures.push_back({section.id, plot});
  return section;
}

}  // namespace scatterlab::report
