#pragma once
// A scalar tally as every command prints it: its batch mean and the standard error stored with
// it (never recomputed, say from the bins of a sibling tally), in one text. `simulate`,
// `searchlight`, `validate searchlight` and `info` print their totals through these functions, so
// the same run shows the same figures wherever it is printed.

#include <string>
#include <string_view>
#include <vector>

#include "scatterlab/tally/tally_result.hpp"

namespace scatterlab {

struct ScalarEstimate {
  double mean = 0.0;
  double stderr_of_mean = 0.0;
};

// The scalar tally called `name` among `tallies`; 0 ± 0 when the run has none.
ScalarEstimate scalar_estimate(const std::vector<TallyResult>& tallies, std::string_view name);

// "0.0713353 ± 0.00082": six significant digits for the mean, two for its standard error.
std::string estimate_text(const ScalarEstimate& estimate);

// How far a model's value lies from the Monte Carlo mean, in standard errors: "(-2.9 sigma)",
// (mean - model) / stderr; empty when the standard error is 0 (an exact tally).
std::string sigma_text(const ScalarEstimate& monte_carlo, double model);

}  // namespace scatterlab
