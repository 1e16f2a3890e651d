#pragma once
// How the volume tallies (fluence, flux, radiance) are estimated.

#include <string>

namespace scatterlab {

enum class Estimator {
  collision,     // score at each collision, weight 1 / sigma_t (the paper's estimator)
  track_length,  // score the length of every flight inside each bin
};

std::string to_string(Estimator estimator);

}  // namespace scatterlab
