#pragma once
// d'Eon & Irving 2011's point-source comparison (Vavassori §4.1, Fig. 4.2; §4.4): an isotropic
// point source in an infinite medium with isotropic scattering, the fluence on spherical shells
// from the Monte Carlo, the exact transport solution, classical diffusion and Grosjean's
// approximation, and each model's relative error over the near (rho < 1 mfp) and far ranges.
// Everything is compared as shell averages (what the Monte Carlo tally estimates), so no model
// is charged for the binning.

#include <cstdint>
#include <string>
#include <vector>

#include "scatterlab/tally/axis.hpp"
#include "scatterlab/transport/run_settings.hpp"

namespace scatterlab {

struct PointSourceComparisonSettings {
  std::uint64_t photons = 1'000'000;              // per albedo
  std::uint32_t batches = RunSettings{}.batches;  // as simulate: the same standard errors
  std::uint64_t seed = 1;
  int threads = 0;                  // 0: all hardware threads
  UniformAxis rho{0.0, 10.0, 100};  // shells, mfp
  double near_limit = 1.0;          // mfp: near is rho1 <= near_limit
};

// Mean |model - exact| / exact over the shells of a range.
struct RangeError {
  double near = 0.0;
  double far = 0.0;
};

struct PointSourceComparison {
  double albedo = 0.0;
  std::vector<double> rho_lo, rho_hi;  // shell edges, mfp
  // Shell-averaged fluence, mfp^-2 per unit source power.
  std::vector<double> monte_carlo, monte_carlo_stderr, exact, diffusion, grosjean;
  RangeError diffusion_error, grosjean_error;  // over every shell of the range
  RangeError monte_carlo_error;                // over the shells compared below
  // Monte Carlo against the exact solution in units of its own standard error, over the shells
  // that expect at least 100 collisions (fewer and the batch error is not Gaussian).
  double max_abs_z = 0.0;
  double within_3_sigma = 0.0;  // fraction of those shells with |z| < 3
  int compared_shells = 0;
  double wall_seconds = 0.0;
};

PointSourceComparison compare_point_source(double albedo,
                                           const PointSourceComparisonSettings& settings);

}  // namespace scatterlab
