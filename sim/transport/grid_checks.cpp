#include "scatterlab/transport/grid_checks.hpp"

#include <fmt/format.h>

#include <cmath>

#include "scatterlab/core/error.hpp"

namespace scatterlab {

void check_bins(const UniformAxis& axis, const std::string& name) {
  if (axis.bins < 1 || axis.bins > max_axis_bins) {
    throw InputError("grid." + name + ".bins", fmt::format("got {}", axis.bins),
                     "an integer in [1, 100000]");
  }
}

void check_from_zero(const UniformAxis& axis, const std::string& name, const std::string& origin,
                     const std::string& unit) {
  if (axis.min != 0.0) {
    throw InputError("grid." + name + ".min", fmt::format("got {}", axis.min),
                     "0 (" + origin + ")");
  }
  if (!(axis.max > 0.0) || !std::isfinite(axis.max)) {
    throw InputError("grid." + name + ".max", fmt::format("got {}", axis.max),
                     "a finite number > 0 (in " + unit + ")");
  }
  check_bins(axis, name);
}

}  // namespace scatterlab
