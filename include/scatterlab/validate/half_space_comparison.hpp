#pragma once
// The searchlight comparison (Bitterli §2.3, §3.6.3): each half-space model's R_d(r) averaged
// over the annuli of an r grid and phi(r, z) over its cells, next to Monte Carlo curves given as
// input (mean and standard error per bin, per unit incident power), with each model's error.
// Models are per unit power entering the medium; they are multiplied by entry_transmittance
// (1 - specular reflectance at the entry point) so that both sides are per unit incident power.

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "scatterlab/models/half_space_medium.hpp"

namespace scatterlab {

struct MonteCarloCurve {
  std::vector<double> mean;
  std::vector<double> stderr_of_mean;
};

struct ModelCurve {
  std::string model;           // "dipole", "better_dipole", "grosjean"
  std::vector<double> values;  // per bin (fluence: row-major [r][z])
  double total = 0.0;          // R_dr (reflectance curves only)
  // Mean |model - MC| / MC over bins with r1 <= near_limit (near) and beyond (far), over the
  // bins where MC is resolved (mean > 3 stderr); NaN without Monte Carlo.
  double near_error = 0.0, far_error = 0.0;
};

struct HalfSpaceComparison {
  HalfSpaceMedium medium;
  double entry_transmittance = 1.0;
  double near_limit = 1.0;  // in the medium's length unit
  std::vector<double> r_edges, z_edges;
  std::vector<ModelCurve> reflectance;  // R_d annulus averages, 1 / length^2
  std::vector<ModelCurve> fluence;      // phi cell averages, 1 / length^2 (empty if no z grid)
  std::optional<MonteCarloCurve> reflectance_mc, fluence_mc;
};

// Builds every model's curves; Monte Carlo curves (optional) must match the grids' bin counts
// (InputError "monte_carlo" otherwise). An empty z_edges skips the fluence.
HalfSpaceComparison compare_half_space(const HalfSpaceMedium& medium, double entry_transmittance,
                                       std::span<const double> r_edges,
                                       std::span<const double> z_edges,
                                       std::optional<MonteCarloCurve> reflectance_mc = {},
                                       std::optional<MonteCarloCurve> fluence_mc = {},
                                       double near_limit = 1.0);

}  // namespace scatterlab
