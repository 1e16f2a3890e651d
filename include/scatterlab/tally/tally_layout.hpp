#pragma once
// Where each requested tally lives in one flat score buffer, and how raw per-photon scores
// become physical estimates (DESIGN.md, Normalisation).
//
// Buffer: [all orders][unscattered][once scattered][multiply scattered][scalars], where the three
// per-order blocks exist only when the scene splits tallies by scattering order. Each score goes
// to the all-orders block and, when split, to its order's block too: the total then carries its
// own batch variance instead of a sum of correlated parts. A block is
// [radiance r*z*theta*phi][fluence r*z][flux r*z*2][fluence_spherical rho], each part present
// only when requested.

#include <cstddef>
#include <string>
#include <vector>

#include "scatterlab/tally/tally_result.hpp"
#include "scatterlab/transport/simulation.hpp"

namespace scatterlab {

// Scalars that account for every photon's energy (per unit incident power).
enum class ScalarScore : std::size_t {
  absorbed = 0,           // absorbed inside the (r, z) grid
  absorbed_outside_grid,  // absorbed anywhere else
  escaped,                // crossed the escape radius (only with a finite escape radius)
  absorption_depth,       // sum of z at absorption: its mean is <z_abs> in mfp
  count
};

struct TallyLayout {
  static constexpr std::size_t absent = static_cast<std::size_t>(-1);

  explicit TallyLayout(const SimulationSpec& spec);

  std::size_t radiance = absent;
  std::size_t fluence = absent;
  std::size_t flux = absent;
  std::size_t fluence_spherical = absent;
  std::size_t scalars = 0;

  bool split_by_order = false;
  std::size_t block_size = 0;  // one block of all the binned tallies
  std::size_t size = 0;  // the whole buffer

  // Strides of the row-major radiance array [r][z][theta][phi] and of [r][z].
  std::size_t theta_bins = 0, phi_bins = 0, z_bins = 0, r_bins = 0, rho_bins = 0;

  // Offset of the block for photons that have scattered `order` times (0, 1, or 2 meaning
  // two or more); only meaningful when split_by_order.
  std::size_t order_block(int order) const {
    return (1 + static_cast<std::size_t>(order < 2 ? order : 2)) * block_size;
  }
  std::size_t scalar(ScalarScore s) const { return scalars + static_cast<std::size_t>(s); }
};

// Turns the batch mean and standard error of raw per-photon scores (counts or path lengths per
// bin) into named tallies with units, dividing by bin volume and solid angle.
std::vector<TallyResult> finalize_tallies(const SimulationSpec& spec, const TallyLayout& layout,
                                          const std::vector<double>& raw_mean,
                                          const std::vector<double>& raw_stderr);

}  // namespace scatterlab
