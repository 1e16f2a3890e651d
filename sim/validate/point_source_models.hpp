#pragma once
// The point source's fluence models on spherical shells (d'Eon & Irving 2011, as Vavassori §4.1,
// Fig. 4.2 plots them), each a shell average per unit source power, as the Monte Carlo's
// fluence_spherical tally estimates (models/point_source_exact.hpp):
//   exact      the exact transport solution       (models/point_source_exact.hpp)
//   diffusion  classical diffusion                (models/point_source_diffusion.hpp)
//   grosjean   Grosjean's approximation           (models/point_source_grosjean.hpp)
// `validate deon` compares them with the Monte Carlo, and `simulate --source point` writes them
// under /models/<model>/fluence_spherical, so that the file holds its own reference curves.

#include <vector>

#include "scatterlab/io/simulation_file.hpp"
#include "scatterlab/tally/tally_result.hpp"
#include "scatterlab/transport/simulation.hpp"

namespace scatterlab {

// The three models' shell averages for isotropic scattering, albedo in [0, 1), on the shells
// between consecutive `rho_edges` (mfp, starting at 0 or more), in mfp^-2 per unit power.
struct PointSourceCurves {
  std::vector<double> exact, diffusion, grosjean;
};
PointSourceCurves point_source_shell_averages(double albedo, const std::vector<double>& rho_edges);

// The curves for a simulate run's /models, in the run's length unit and with the units of its
// `fluence_spherical` tally. None for a run without that tally (the beam). The models hold for an
// infinite medium that scatters isotropically and absorbs: a run with g != 0, albedo 1 or an
// escape radius (which stops photons the infinite medium would send back) gets, per model, a
// group whose note says why it has no curve.
std::vector<ModelResult> point_source_model_curves(const InfiniteMediumSpec& spec,
                                                   const std::vector<TallyResult>& tallies);

}  // namespace scatterlab
