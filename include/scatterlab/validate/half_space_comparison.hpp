#pragma once
// The searchlight comparison (Bitterli §2.3, §3.6.3), like with like: each half-space model
// next to the Monte Carlo part whose definition matches it, with each model's error.
//   - diffusion models (dipole, better dipole, quantized diffusion, photon beam diffusion) model
//     the light scattered at least twice (models/dipole.hpp): against the Monte Carlo's _multiple
//     part;
//   - the exact once-scattered solution (refract/half_space_single_scatter.hpp): against the
//     _single part;
//   - each diffusion model plus the exact once-scattered light ("<model>+single_scatter"), and
//     the Grosjean beam (models/grosjean_beam.hpp), model every scattered photon: against the
//     total (the unscattered beam never leaves a half-space, so total = single + multiple).
// R_d(r) is averaged over the annuli of an r grid and phi(r, z) over its cells. Models are per
// unit power entering the medium; they are multiplied by entry_transmittance (1 - specular
// reflectance at the entry point) so that both sides are per unit incident power. Normal
// incidence only, eta in [0.5, 2.5] (the Fresnel-moment fits).

#include <map>
#include <span>
#include <string>
#include <vector>

#include "scatterlab/models/grosjean_beam.hpp"
#include "scatterlab/models/half_space_medium.hpp"

namespace scatterlab {

struct MonteCarloCurve {
  std::vector<double> mean;
  std::vector<double> stderr_of_mean;
  double total = 0.0;  // the scalar tally of the same part (reflectance only)
  double total_stderr = 0.0;
};

// The suffix of the Monte Carlo tally that holds `part`: "", "_single" or "_multiple".
std::string tally_suffix(ModelPart part);

struct ModelCurve {
  std::string model;           // "dipole", "better_dipole+single_scatter", ...
  ModelPart part = ModelPart::multiple;  // the scattering orders it models
  std::vector<double> values;  // per bin (fluence: row-major [r][z])
  double total = 0.0;          // R_dr (reflectance curves only)
  std::vector<double> error;   // the exact solution's quadrature error per bin, else empty
  double total_error = 0.0;
  // Mean |model - MC| / MC over bins with r1 <= near_limit (near) and beyond (far), over the
  // bins where the Monte Carlo of the same part is resolved (mean > 3 stderr); NaN without it.
  double near_error = 0.0, far_error = 0.0;
};

struct HalfSpaceComparison {
  HalfSpaceMedium medium;
  double entry_transmittance = 1.0;
  double near_limit = 1.0;  // in the medium's length unit
  std::vector<double> r_edges, z_edges;
  std::vector<ModelCurve> reflectance;  // R_d annulus averages, 1 / length^2
  std::vector<ModelCurve> fluence;      // phi cell averages, 1 / length^2 (empty if no z grid)
  std::map<ModelPart, MonteCarloCurve> reflectance_mc, fluence_mc;  // by part, as given
};

// Builds every model's curves; Monte Carlo curves (optional, by part) must match the grids' bin
// counts (InputError "monte_carlo" otherwise). An empty z_edges skips the fluence.
HalfSpaceComparison compare_half_space(const HalfSpaceMedium& medium, double entry_transmittance,
                                       std::span<const double> r_edges,
                                       std::span<const double> z_edges,
                                       std::map<ModelPart, MonteCarloCurve> reflectance_mc = {},
                                       std::map<ModelPart, MonteCarloCurve> fluence_mc = {},
                                       double near_limit = 1.0);

}  // namespace scatterlab
