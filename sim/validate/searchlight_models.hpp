#pragma once
// Every model's curves on a searchlight run's grid, in the run's normalisation (per unit incident
// power), for /models in the same file, each under the name of the Monte Carlo tally it is to be
// compared with (validate/half_space_comparison.hpp says which part each model describes):
//   single_scatter            reflectance_single, diffuse_reflectance_single (exact)
//   dipole, better_dipole,    reflectance_multiple, diffuse_reflectance_multiple, and with the
//   quantized_diffusion       model fluence, fluence_multiple
//   photon_beam_diffusion     reflectance_multiple, diffuse_reflectance_multiple
//   scatterlab_grosjean_beam  reflectance_multiple, reflectance (all orders), their totals, and
//                             fluence (all orders)
// A model the run's conditions leave out (oblique incidence: every model here is for normal
// incidence; eta outside [0.5, 2.5] for the diffusion models) gets a group with a "note"
// attribute that says why, instead of nothing.

#include <vector>

#include "scatterlab/io/simulation_file.hpp"
#include "scatterlab/transport/searchlight.hpp"

namespace scatterlab {

// `specular_reflectance`: the run's entry reflectance R(0); the models carry 1 - R(0).
// `with_fluence`: also each diffusion model's phi(r, z) cell averages (when the run tallies the
// fluence). They are 2-D adaptive integrals, about 1 ms per cell and model: about a minute on
// the default 200 x 100 grid, so they are asked for, not assumed.
std::vector<ModelResult> searchlight_model_curves(const HalfSpaceSpec& spec,
                                                  double specular_reflectance,
                                                  bool with_fluence = false);

}  // namespace scatterlab
