#pragma once
// Where each half-space tally lives in one flat score buffer, and how raw per-photon counts
// become physical estimates (DESIGN.md, HDF5 layout: reflectance [r], diffuse_reflectance,
// specular_reflectance, per-order siblings).
//
// Buffer: [all orders][unscattered][once scattered][multiply scattered][scalars]. Every score
// goes to the all-orders block and to its order's block, so that each total carries its own
// batch variance. A block is [reflectance r][exitant radiance r*theta_o][fluence r*z]
// [diffuse_reflectance], the fluence only when requested; the scalars are absorbed and escaped.
// Counts are per photon that entered the medium; finalize scales them by the transmitted power.

#include <cstddef>
#include <vector>

#include "scatterlab/tally/tally_result.hpp"
#include "scatterlab/transport/searchlight.hpp"

namespace scatterlab {

struct HalfSpaceLayout {
  static constexpr std::size_t absent = static_cast<std::size_t>(-1);
  static constexpr std::size_t blocks = 4;  // all orders, unscattered, single, multiple

  explicit HalfSpaceLayout(const SearchlightSpec& spec);

  std::size_t reflectance = 0;
  std::size_t radiance = 0;
  std::size_t fluence = absent;
  std::size_t diffuse = 0;
  std::size_t block_size = 0;
  std::size_t absorbed = 0;
  std::size_t escaped = 0;
  std::size_t size = 0;

  std::size_t r_bins = 0, z_bins = 0, theta_bins = 0;

  // Offset of the block of light scattered `order` times (0, 1, or 2 meaning two or more).
  std::size_t order_block(int order) const {
    return (1 + static_cast<std::size_t>(order < 2 ? order : 2)) * block_size;
  }
};

// The power entering the medium and that reflected at entry, per unit incident power.
struct EntryPower {
  double specular = 0.0;     // Fresnel reflectance at the angle of incidence
  double transmitted = 1.0;  // 1 - specular
};

// Turns the batch mean and standard error of raw counts per entering photon into named tallies
// per unit incident power, with units.
std::vector<TallyResult> finalize_half_space_tallies(const SearchlightSpec& spec,
                                                     const HalfSpaceLayout& layout,
                                                     const EntryPower& entry,
                                                     const std::vector<double>& raw_mean,
                                                     const std::vector<double>& raw_stderr);

}  // namespace scatterlab
