#include "scatterlab/core/medium.hpp"

#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "scatterlab/core/error.hpp"

namespace scatterlab {

void Medium::validate() const {
  if (!(albedo >= 0.0 && albedo <= 1.0)) {
    throw InputError("medium.albedo", fmt::format("got {}", albedo), "a number in [0, 1]");
  }
  if (!(sigma_t > 0.0) || !std::isfinite(sigma_t)) {
    throw InputError("medium.sigma_t", fmt::format("got {}", sigma_t), "a finite number > 0");
  }
  if (!(std::abs(g) < 1.0)) {
    throw InputError("medium.g", fmt::format("got {}", g), "a number with |g| < 1");
  }
}

Medium Medium::from_albedo(double albedo, double sigma_t, double g, std::string length_unit) {
  Medium medium{albedo, sigma_t, g, std::move(length_unit)};
  medium.validate();
  return medium;
}

Medium Medium::from_coefficients(double sigma_a, double sigma_s, double g,
                                 std::string length_unit) {
  if (!(sigma_a >= 0.0) || !std::isfinite(sigma_a)) {
    throw InputError("medium.sigma_a", fmt::format("got {}", sigma_a), "a finite number >= 0");
  }
  if (!(sigma_s >= 0.0) || !std::isfinite(sigma_s)) {
    throw InputError("medium.sigma_s", fmt::format("got {}", sigma_s), "a finite number >= 0");
  }
  const double sigma_t = sigma_a + sigma_s;
  if (!(sigma_t > 0.0)) {
    throw InputError("medium.sigma_s", "sigma_a + sigma_s is 0", "sigma_a + sigma_s > 0");
  }
  return from_albedo(sigma_s / sigma_t, sigma_t, g, std::move(length_unit));
}

bool is_physical_length_unit(std::string_view unit) {
  return unit == "um" || unit == "mm" || unit == "cm" || unit == "m";
}

double millimetres_per(std::string_view unit) {
  if (unit == "um") return 1e-3;
  if (unit == "mm") return 1.0;
  if (unit == "cm") return 10.0;
  if (unit == "m") return 1000.0;
  throw InputError("length_unit", fmt::format("got \"{}\"", unit),
                   "\"um\", \"mm\", \"cm\" or \"m\"");
}

}  // namespace scatterlab
