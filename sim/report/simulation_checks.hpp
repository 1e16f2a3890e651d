#pragma once
// Small helpers the report's Monte Carlo sections share.

#include <cmath>
#include <string>

#include "scatterlab/transport/simulate.hpp"

namespace scatterlab::report {

inline const TallyResult& tally(const SimulationOutput& output, const std::string& name) {
  for (const TallyResult& t : output.tallies) {
    if (t.name == name) return t;
  }
  throw std::logic_error("report: simulation has no tally " + name);
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
