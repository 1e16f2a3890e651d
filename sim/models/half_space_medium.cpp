#include "scatterlab/models/half_space_medium.hpp"

#include <cmath>
#include <string>

#include "scatterlab/core/error.hpp"

namespace scatterlab {

HalfSpaceMedium HalfSpaceMedium::from_albedo(double albedo, double g, double eta) {
  if (!(albedo >= 0.0 && albedo <= 1.0)) {
    throw InputError("albedo", "got " + std::to_string(albedo), "a number in [0, 1]");
  }
  HalfSpaceMedium medium{1.0 - albedo, albedo, g, eta};
  medium.validate();
  return medium;
}

void HalfSpaceMedium::validate() const {
  if (!(sigma_a >= 0.0) || !std::isfinite(sigma_a)) {
    throw InputError("sigma_a", "got " + std::to_string(sigma_a), "a finite number >= 0");
  }
  if (!(sigma_s >= 0.0) || !std::isfinite(sigma_s)) {
    throw InputError("sigma_s", "got " + std::to_string(sigma_s), "a finite number >= 0");
  }
  if (!(sigma_a + sigma_s > 0.0)) {
    throw InputError("sigma_s", "sigma_a + sigma_s is 0", "sigma_a + sigma_s > 0");
  }
  if (!(std::abs(g) < 1.0)) {
    throw InputError("g", "got " + std::to_string(g), "a number with |g| < 1");
  }
  if (!(eta >= 0.5 && eta <= 2.5)) {
    throw InputError("eta", "got " + std::to_string(eta), "a relative index in [0.5, 2.5]");
  }
}

}  // namespace scatterlab
