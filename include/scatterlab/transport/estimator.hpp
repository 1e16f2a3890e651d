#pragma once
// How the volume tallies (fluence, flux, radiance) are estimated: the scene's choice, and the
// walk's, which is `none` when a run has no volume tally (the engine decides; a scene never says
// none).

#include <string>

namespace scatterlab {

enum class Estimator {
  none,          // nothing scored in the volume: a run with surface tallies alone
  collision,     // score at each collision, weight 1 / sigma_t (the paper's estimator)
  track_length,  // score the length of every flight inside each bin
};

std::string to_string(Estimator estimator);

}  // namespace scatterlab
