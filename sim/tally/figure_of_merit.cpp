#include "scatterlab/tally/figure_of_merit.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace scatterlab {

double relative_standard_error(std::span<const double> mean,
                               std::span<const double> stderr_of_mean) {
  std::vector<double> relative;
  for (std::size_t i = 0; i < mean.size() && i < stderr_of_mean.size(); ++i) {
    if (mean[i] != 0.0) relative.push_back(stderr_of_mean[i] / std::abs(mean[i]));
  }
  if (relative.empty()) return std::numeric_limits<double>::quiet_NaN();
  const std::size_t middle = relative.size() / 2;
  const auto at_middle = relative.begin() + static_cast<std::ptrdiff_t>(middle);
  std::nth_element(relative.begin(), at_middle, relative.end());
  const double upper = *at_middle;
  if (relative.size() % 2 == 1) return upper;
  return 0.5 * (*std::max_element(relative.begin(), at_middle) + upper);
}

double figure_of_merit(double relative_error, double seconds) {
  if (!(relative_error > 0.0) || !(seconds > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return 1.0 / (relative_error * relative_error * seconds);
}

}  // namespace scatterlab
