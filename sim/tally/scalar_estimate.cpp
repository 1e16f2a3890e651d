#include "scatterlab/tally/scalar_estimate.hpp"

#include <fmt/format.h>

namespace scatterlab {

ScalarEstimate scalar_estimate(const std::vector<TallyResult>& tallies, std::string_view name) {
  const TallyResult* t = find_tally(tallies, name);
  if (t == nullptr || t->mean.empty()) return {};
  return {t->mean[0], t->stderr_of_mean[0]};
}

std::string estimate_text(const ScalarEstimate& estimate) {
  return fmt::format("{:.6g} ± {:.2g}", estimate.mean, estimate.stderr_of_mean);
}

std::string sigma_text(const ScalarEstimate& monte_carlo, double model) {
  if (!(monte_carlo.stderr_of_mean > 0.0)) return "";
  return fmt::format("({:+.1f} sigma)", (monte_carlo.mean - model) / monte_carlo.stderr_of_mean);
}

}  // namespace scatterlab
