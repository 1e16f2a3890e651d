#include "scatterlab/transport/length_units.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <limits>

#include "scatterlab/core/error.hpp"

namespace scatterlab {

void check_length_unit(const Medium& medium) {
  if (medium.length_unit != "mfp" && !is_physical_length_unit(medium.length_unit)) {
    throw InputError("medium.length_unit", fmt::format("got \"{}\"", medium.length_unit),
                     "one of \"mfp\", \"um\", \"mm\", \"cm\", \"m\"");
  }
  // A mean free path is 1 / sigma_t, so sigma_t in 1/mfp is 1 by definition; anything else means
  // the coefficients were given in a physical unit that the file did not name.
  if (medium.length_unit == "mfp" && std::abs(medium.sigma_t - 1.0) > 1e-12) {
    throw InputError(
        "medium.length_unit",
        fmt::format("\"mfp\" makes sigma_t = 1 by definition, but sigma_t is {}", medium.sigma_t),
        "a physical unit (\"um\", \"mm\", \"cm\", \"m\") for the coefficients, or "
        "sigma_t = 1");
  }
}

void check_length_axis_span(const UniformAxis& axis, const std::string& name,
                            const Medium& medium) {
  const double mfp = mfp_per_length_unit(medium);
  const std::string& unit = medium.length_unit;
  const double limit = max_grid_mfp / mfp;  // in the unit
  const std::string span = fmt::format("ends within +-{:g} mfp and bins at least {:g} mfp wide",
                                       max_grid_mfp, min_bin_mfp);
  if (!(std::abs(axis.min) * mfp <= max_grid_mfp)) {
    throw InputError("grid." + name + ".min", fmt::format("got {} {}", axis.min, unit),
                     fmt::format("a number in [{:g}, {:g}] {} ({})", -limit, limit, unit, span));
  }
  const double lowest = axis.min + axis.bins * (min_bin_mfp / mfp);
  if (!(std::abs(axis.max) * mfp <= max_grid_mfp) ||
      !((axis.max - axis.min) * mfp >= axis.bins * min_bin_mfp)) {
    throw InputError(
        "grid." + name + ".max",
        fmt::format("got {} {} with grid.{}.min = {} and {} bins", axis.max, unit, name, axis.min,
                    axis.bins),
        fmt::format("a number in [{:g}, {:g}] {} ({})", lowest, limit, unit, span));
  }
}

void check_escape_radius_span(double escape_radius, const Medium& medium) {
  const double mfp = mfp_per_length_unit(medium);
  if (std::isfinite(escape_radius) && !std::isfinite(escape_radius * mfp)) {
    throw InputError("run.escape_radius",
                     fmt::format("got {} {}, beyond the largest double in mfp at sigma_t = {}",
                                 escape_radius, medium.length_unit, medium.sigma_t),
                     fmt::format("a number in (0, {:g}] {}, or inf",
                                 std::numeric_limits<double>::max() / mfp, medium.length_unit));
  }
}

UniformAxis length_axis_in_mfp(const UniformAxis& axis, double mfp_per_unit) {
  UniformAxis scaled = axis;
  scaled.min = axis.min * mfp_per_unit;
  scaled.max = axis.max * mfp_per_unit;
  return scaled;
}

}  // namespace scatterlab
