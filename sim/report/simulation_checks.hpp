#pragma once
// Small helpers the report's Monte Carlo sections share.

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

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

}  // namespace scatterlab::report
