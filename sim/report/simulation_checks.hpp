#pragma once
// Small helpers the report's Monte Carlo sections share.

#include <fmt/format.h>

#include <cmath>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "scatterlab/report/section.hpp"
#include "scatterlab/report/suites.hpp"
#include "scatterlab/transport/run_settings.hpp"
#include "scatterlab/transport/simulate.hpp"

namespace scatterlab::report {

inline const TallyResult& tally(const std::vector<TallyResult>& tallies, const std::string& name) {
  const TallyResult* t = find_tally(tallies, name);
  if (t == nullptr) throw std::logic_error("report: run has no tally " + name);
  return *t;
}

// Least-squares slope of log(y) against log(x): the exponent of a power law y ~ x^slope.
inline double log_log_slope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// A point's wall time, drawn beside it on an error-against-photons figure ("0.42 s").
inline std::string wall_time_label(double seconds) { return fmt::format("{:.2g} s", seconds); }

inline std::vector<std::string> wall_time_labels(const std::vector<double>& seconds) {
  std::vector<std::string> labels;
  for (const double s : seconds) labels.push_back(wall_time_label(s));
  return labels;
}

// A report run: `photons` in 32 batches (the standard errors come from their spread), from
// `seed`, on the profile's threads.
inline RunSettings report_run(std::uint64_t photons, std::uint64_t seed, const Profile& profile) {
  RunSettings run;
  run.photons = photons;
  run.batches = 32;
  run.seed = seed;
  run.threads = profile.threads;
  return run;
}

// NaN or Inf anywhere in a run's tallies (means and standard errors).
inline int count_non_finite(const std::vector<TallyResult>& tallies) {
  int count = 0;
  for (const TallyResult& t : tallies) {
    for (std::size_t i = 0; i < t.size(); ++i) {
      count += !std::isfinite(t.mean[i]) || !std::isfinite(t.stderr_of_mean[i]);
    }
  }
  return count;
}

// An extremes section's findings: "N of M checks pass over K cells.", a cell a row of its table.
inline std::string checks_over_cells(const Section& section) {
  return fmt::format("{} of {} checks pass over {} cells.\n", section.checks_passed(),
                     section.checks.size(), section.table.rows.size());
}

// A Monte Carlo estimate and its standard error.
struct Estimate {
  double mean = 0.0, stderr_of_mean = 0.0;
};

// A run's one-value tally as an estimate.
inline Estimate estimate(const TransportOutput& out, const std::string& name) {
  const TallyResult& t = tally(out.tallies, name);
  return {t.mean[0], t.stderr_of_mean[0]};
}

// |estimate - exact| within 5 standard errors; where no photon was scored, an exact value that
// few photons would have missed (below 3 / photons).
inline bool agrees(const Estimate& e, double exact, double photons) {
  if (e.stderr_of_mean > 0.0) return std::abs(e.mean - exact) <= 5.0 * e.stderr_of_mean;
  return e.mean == exact || (e.mean == 0.0 && exact * photons < 3.0);
}

inline double z_score(const Estimate& e, double exact) {
  return e.stderr_of_mean > 0.0 ? (e.mean - exact) / e.stderr_of_mean : 0.0;
}

// Energy in a run whose every photon ends in exactly one of `fixed` (a part known before any
// photon runs, or one tally) and the one-value `totals`: the residual of their sum against 1, and
// of the sum with each total split into its scattering orders (_unscattered, _single,
// _multiple). Both 0 to rounding.
struct EnergyResiduals {
  double total = 0.0, by_order = 0.0;
};

inline EnergyResiduals energy_residuals(const TransportOutput& out, double fixed,
                                        std::initializer_list<std::string> totals) {
  EnergyResiduals r{fixed, fixed - 1.0};
  for (const std::string& total : totals) {
    r.total += estimate(out, total).mean;
    for (const char* order : {"_unscattered", "_single", "_multiple"}) {
      r.by_order += estimate(out, total + order).mean;
    }
  }
  r.total -= 1.0;
  return r;
}

// Estimates by name as the one-value tallies of a run of `seconds`, for a section whose runs are
// integrals rather than transport (add_error_against_run_time reads runs as TransportOutput).
inline TransportOutput scalar_output(
    double seconds, const std::vector<std::pair<std::string, Estimate>>& estimates) {
  TransportOutput out;
  out.wall_seconds = seconds;
  for (const auto& [name, e] : estimates) {
    TallyResult t;
    t.name = name;
    t.mean = {e.mean};
    t.stderr_of_mean = {e.stderr_of_mean};
    out.tallies.push_back(std::move(t));
  }
  return out;
}

// A quantity whose error a section follows against run time, and its exact value.
struct ConvergingQuantity {
  std::string name;    // its column in the table, e.g. "diffuse_reflectance"
  std::string symbol;  // on the figure's axis, matplotlib mathtext: "$R_\\mathrm{d}$"
  double exact = 0.0;
  double rounding = 0.0;  // of a reference printed to few digits, added to the tolerance
};

// What a budget counts: photons for the Monte Carlo transport, samples for an integral.
struct Budget {
  std::string column = "photons";  // the table's column, and "<column>_per_second"
  std::string words = "photons";   // in the checks and on the figure's axis
};

// Error against run time: `run(budget, seed)` at doubling budgets (6 from 2e4 quick, 9 from 1e5
// in full, each its own seed from profile.seed up) gives each quantity's estimate. Each budget is
// checked within 5 standard errors of the exact value (plus its rounding), and the slope of log
// stderr against log budget in [-0.6, -0.4] (N^-1/2). Fills the section's table (budget, seconds,
// budget per second, then per quantity its value, stderr, relative error and z; with several
// quantities each column is prefixed by its name), one figure per quantity (`title` above its
// name) and its findings.
template <class Run>
void add_error_against_run_time(Section& section, const Profile& profile,
                                const std::vector<ConvergingQuantity>& quantities,
                                const std::string& title, const Run& run,
                                const Budget& budget = {}) {
  const bool several = quantities.size() > 1;
  const auto column = [&](const ConvergingQuantity& q, const std::string& what) {
    return several ? q.name + "_" + what : what;
  };
  section.table.columns = {budget.column, "seconds", budget.column + "_per_second"};
  for (const ConvergingQuantity& q : quantities) {
    section.table.columns.insert(
        section.table.columns.end(),
        {q.name, column(q, "stderr"), column(q, "relative_error"), column(q, "z")});
  }
  struct Series {
    PlotSeries errors{"|Monte Carlo − exact| / exact", {}, {}, {}, true, "monte_carlo"};
    PlotSeries predicted{"standard error / exact", {}, {}, {}, false, "standard_error"};
    std::vector<double> standard_errors;
  };
  std::vector<Series> series(quantities.size());
  std::vector<double> photon_counts;
  const int budgets = profile.quick ? 6 : 9;
  for (int b = 0; b < budgets; ++b) {
    const auto photons =
        static_cast<std::uint64_t>((profile.quick ? 2e4 : 1e5) * std::ldexp(1.0, b));
    const TransportOutput out = run(photons, profile.seed + static_cast<std::uint64_t>(b));
    section.non_finite_values += count_non_finite(out.tallies);
    std::vector<std::string> row = {
        fmt::format("{}", photons), fmt::format("{:.3g}", out.wall_seconds),
        fmt::format("{:.4g}", static_cast<double>(photons) / out.wall_seconds)};
    for (std::size_t i = 0; i < quantities.size(); ++i) {
      const ConvergingQuantity& q = quantities[i];
      const Estimate e = estimate(out, q.name);
      const double z = (e.mean - q.exact) / e.stderr_of_mean;
      const double relative = std::abs(e.mean - q.exact) / q.exact;
      section.checks.push_back(
          {fmt::format("{} {}: {}z-score {:.2f} within 5{}", photons, budget.words,
                       several ? q.name + " " : "", z,
                       q.rounding > 0.0 ? fmt::format(" (and {:g})", q.rounding) : ""),
           std::abs(e.mean - q.exact) <= 5.0 * e.stderr_of_mean + q.rounding});
      row.insert(row.end(), {fmt::format("{:.7f}", e.mean), fmt::format("{:.2g}", e.stderr_of_mean),
                             fmt::format("{:.3g}", relative), fmt::format("{:.2f}", z)});
      Series& s = series[i];
      s.errors.x.push_back(static_cast<double>(photons));
      s.errors.y.push_back(relative);
      s.errors.point_labels.push_back(wall_time_label(out.wall_seconds));
      s.predicted.x.push_back(static_cast<double>(photons));
      s.predicted.y.push_back(e.stderr_of_mean / q.exact);
      s.standard_errors.push_back(e.stderr_of_mean);
    }
    section.table.rows.push_back(std::move(row));
    photon_counts.push_back(static_cast<double>(photons));
  }
  for (std::size_t i = 0; i < quantities.size(); ++i) {
    const ConvergingQuantity& q = quantities[i];
    const double slope = log_log_slope(photon_counts, series[i].standard_errors);
    section.checks.push_back({fmt::format("{}slope of log stderr against log {} {:.3f} in "
                                          "[-0.6, -0.4]",
                                          several ? q.name + ": " : "", budget.words, slope),
                              slope >= -0.6 && slope <= -0.4});
    section.findings += fmt::format("{}tandard error falls as {}^{:.3f}.\n",
                                    several ? "The " + q.name + "'s s" : "S", budget.words, slope);
    // N^-1/2 through the first standard error: where a Monte Carlo's error should fall.
    PlotSeries ideal{"$\\propto N^{-1/2}$", {}, {}, {}, false, "straight"};
    for (const double n : photon_counts) {
      ideal.x.push_back(n);
      ideal.y.push_back(series[i].predicted.y.front() * std::sqrt(photon_counts.front() / n));
    }
    LinePlot plot{fmt::format("{}:\nerror of {} against {} (labels: wall time)", title, q.symbol,
                              budget.words),
                  budget.words,
                  "relative error of " + q.symbol,
                  AxisScale::log,
                  true,
                  {series[i].errors, series[i].predicted, ideal}};
    section.figures.push_back({several ? section.id + "_" + q.name : section.id, plot});
  }
}

}  // namespace scatterlab::report
