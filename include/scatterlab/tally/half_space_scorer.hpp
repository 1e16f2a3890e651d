#pragma once
// Scores one half-space photon's events into the buffer laid out by HalfSpaceLayout: a count at
// each exit through the surface (R_d(r), exitant radiance, total) and, when asked for, at each
// collision (fluence, collision estimator with weight 1 / sigma_t = 1 mfp). Raw counts are per
// photon that entered; finalize_half_space_tallies divides by area, solid angle and volume.

#include <cmath>
#include <cstddef>

#include "scatterlab/core/frame.hpp"
#include "scatterlab/tally/angle_binning.hpp"
#include "scatterlab/tally/half_space_layout.hpp"

namespace scatterlab {

class HalfSpaceScorer {
 public:
  HalfSpaceScorer(const SearchlightSpec& spec, const HalfSpaceLayout& layout)
      : r_(spec.grid.r), z_(spec.grid.z), layout_(layout), exit_binning_(spec.grid.theta_o) {}

  // A photon leaves the surface at (x, y, 0) after `order` scatterings, at cos_outside from the
  // outward normal on the outside (after refraction).
  void exit(double* buffer, double x, double y, double cos_outside, int order) const {
    const std::size_t block = layout_.order_block(order);
    add(buffer, layout_.diffuse, block);
    const int ir = r_.index(std::sqrt(x * x + y * y));
    if (ir < 0) return;
    const auto ring = static_cast<std::size_t>(ir);
    add(buffer, layout_.reflectance + ring, block);
    add(buffer,
        layout_.radiance + ring * layout_.theta_bins +
            static_cast<std::size_t>(exit_binning_.bin(cos_outside)),
        block);
  }

  // A collision at `position` after `order` scatterings.
  void collision(double* buffer, const Vec3& position, int order) const {
    const int ir = r_.index(std::sqrt(position.x() * position.x() + position.y() * position.y()));
    const int iz = z_.index(position.z());
    if (ir < 0 || iz < 0) return;
    add(buffer,
        layout_.fluence + static_cast<std::size_t>(ir) * layout_.z_bins +
            static_cast<std::size_t>(iz),
        layout_.order_block(order));
  }

  void absorption(double* buffer) const { buffer[layout_.absorbed] += 1.0; }
  void escape(double* buffer) const { buffer[layout_.escaped] += 1.0; }

 private:
  static void add(double* buffer, std::size_t index, std::size_t order_block) {
    buffer[index] += 1.0;
    buffer[index + order_block] += 1.0;
  }

  UniformAxis r_;
  UniformAxis z_;
  HalfSpaceLayout layout_;
  CosineBinning exit_binning_;
};

}  // namespace scatterlab
