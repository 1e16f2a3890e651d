#pragma once
// Every model's curves on a searchlight run's grid, in the run's normalisation (per unit incident
// power), for /models in the same file: the exact once-scattered reflectance of the refractive
// solver (refract/half_space_single_scatter.hpp) and the diffusion models (classical dipole,
// better dipole, Grosjean; validate/half_space_comparison.hpp) for R_d(r), their totals, and
// their fluence phi(r, z) when the run tallies it.
//
// Both assume normal incidence: an oblique run gets no model curves. The diffusion models also
// need eta in [0.5, 2.5], where the Fresnel-moment fits hold; outside they are left out.

#include <vector>

#include "scatterlab/io/simulation_file.hpp"
#include "scatterlab/transport/searchlight.hpp"

namespace scatterlab {

// `specular_reflectance`: the run's entry reflectance R(0); the models carry 1 - R(0).
// `with_fluence`: also each diffusion model's phi(r, z) cell averages (when the run tallies the
// fluence). They are 2-D adaptive integrals, about 1 ms per cell and model: about a minute on
// the default 200 x 100 grid, so they are asked for, not assumed.
std::vector<ModelResult> searchlight_model_curves(const SearchlightSpec& spec,
                                                  double specular_reflectance,
                                                  bool with_fluence = false);

}  // namespace scatterlab
