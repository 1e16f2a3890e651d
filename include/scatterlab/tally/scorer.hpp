#pragma once
// Scores one photon's events into a flat buffer laid out by TallyLayout: the hot path of every
// tally. Raw scores are per photon: a count per collision (collision estimator, weight
// 1 / sigma_t = 1 in mfp) or a path length (track-length estimator); finalize_tallies divides
// by bin volume and solid angle afterwards.
//
// Frames (DESIGN.md): a point is (r, z) about the beam axis; a direction is (theta, phi) with
// theta from +z and phi from the outward radial direction e_r of the point, towards
// e_phi = z x e_r. Unfolded phi bins cover [0, 2 pi) and need an even count, so that the bins of
// phi and 2 pi - phi mirror each other; folded bins cover [0, pi].

#include <algorithm>
#include <cmath>
#include <vector>

#include "scatterlab/core/frame.hpp"
#include "scatterlab/tally/angle_binning.hpp"
#include "scatterlab/tally/tally_layout.hpp"

namespace scatterlab {

class Scorer {
 public:
  Scorer(const SimulationSpec& spec, const TallyLayout& layout);

  // Per-thread scratch for the track-length estimator's crossing points; sized once.
  std::vector<double> make_crossing_scratch() const;

  // Collision estimator: a photon travelling along `direction` collides at `position` after
  // `order` scatterings.
  void collision(double* buffer, const Vec3& position, const Vec3& direction, int order) const;

  // Track-length estimator: the flight from `start` along `direction` for `length` mfp.
  void flight(double* buffer, std::vector<double>& crossings, const Vec3& start,
              const Vec3& direction, double length, int order) const;

  void absorption(double* buffer, const Vec3& position) const {
    const bool inside = in_grid(position);
    buffer[layout_.scalar(inside ? ScalarScore::absorbed : ScalarScore::absorbed_outside_grid)] += 1.0;
    buffer[layout_.scalar(ScalarScore::absorption_depth)] += position.z();
  }

  void escape(double* buffer) const { buffer[layout_.scalar(ScalarScore::escaped)] += 1.0; }

  bool in_grid(const Vec3& p) const {
    return grid_.r.index(std::sqrt(p.x() * p.x() + p.y() * p.y())) >= 0 && grid_.z.index(p.z()) >= 0;
  }

 private:
  // Adds v at `index` of the all-orders block and, when split, of the order's block.
  void add(double* buffer, std::size_t index, std::size_t order_block, double v) const {
    buffer[index] += v;
    if (layout_.split_by_order) buffer[index + order_block] += v;
  }

  // Adds v to the radiance cell of (cell, theta offset, phi). Unfolded, phi and 2 pi - phi fall
  // in mirrored bins; a direction exactly in the half-plane through the axis (omega . e_phi = 0,
  // as for light scattered once from a pencil beam, a delta in phi on a bin edge) is shared
  // equally between the two bins that meet there.
  void add_radiance(double* buffer, std::size_t base, std::size_t block, double cos_phi,
                    double sin_phi_sign, double v) const {
    const int folded = phi_binning_.bin(cos_phi);
    if (grid_.fold_phi) {
      add(buffer, base + static_cast<std::size_t>(folded), block, v);
    } else if (sin_phi_sign != 0.0) {
      const int bin = sin_phi_sign > 0.0 ? folded : phi_bins_ - 1 - folded;
      add(buffer, base + static_cast<std::size_t>(bin), block, v);
    } else {
      add(buffer, base + static_cast<std::size_t>(folded), block, 0.5 * v);
      add(buffer, base + static_cast<std::size_t>(phi_bins_ - 1 - folded), block, 0.5 * v);
    }
  }

  void flight_cylindrical(double* buffer, std::vector<double>& crossings, const Vec3& start,
                          const Vec3& direction, double length, std::size_t order_block) const;
  void flight_spherical(double* buffer, std::vector<double>& crossings, const Vec3& start,
                        const Vec3& direction, double length, std::size_t order_block) const;

  Grid grid_;
  TallyLayout layout_;
  CosineBinning theta_binning_;
  CosineBinning phi_binning_;  // over [0, pi]
  int phi_bins_ = 1;
  std::vector<double> phi_cotangents_;  // cot of the interior edges of the [0, pi] phi axis
};

inline void Scorer::collision(double* buffer, const Vec3& position, const Vec3& direction,
                              int order) const {
  const std::size_t block = layout_.split_by_order ? layout_.order_block(order) : 0;
  const double r2 = position.x() * position.x() + position.y() * position.y();
  if (layout_.fluence_spherical != TallyLayout::absent) {
    const int shell = grid_.rho.index(std::sqrt(r2 + position.z() * position.z()));
    if (shell >= 0) add(buffer, layout_.fluence_spherical + static_cast<std::size_t>(shell), block, 1.0);
  }
  const double r = std::sqrt(r2);
  const int ir = grid_.r.index(r);
  const int iz = grid_.z.index(position.z());
  if (ir < 0 || iz < 0) return;
  const std::size_t cell = static_cast<std::size_t>(ir) * layout_.z_bins + static_cast<std::size_t>(iz);
  // omega . e_r and omega . e_phi; on the axis e_r is undefined and phi is taken as 0.
  const double radial = r > 0.0 ? (direction.x() * position.x() + direction.y() * position.y()) / r : 0.0;
  if (layout_.fluence != TallyLayout::absent) add(buffer, layout_.fluence + cell, block, 1.0);
  if (layout_.flux != TallyLayout::absent) {
    add(buffer, layout_.flux + 2 * cell, block, radial);
    add(buffer, layout_.flux + 2 * cell + 1, block, direction.z());
  }
  if (layout_.radiance != TallyLayout::absent) {
    double azimuthal =
        r > 0.0 ? (direction.y() * position.x() - direction.x() * position.y()) / r : 0.0;
    const double transverse = std::sqrt(radial * radial + azimuthal * azimuthal);
    // Within rounding of the half-plane through the axis: on it (see add_radiance).
    if (std::abs(azimuthal) <= 1e-12 * transverse) azimuthal = 0.0;
    const double cos_phi = transverse > 0.0 ? radial / transverse : 1.0;
    const std::size_t base =
        layout_.radiance + cell * layout_.theta_bins * layout_.phi_bins +
        static_cast<std::size_t>(theta_binning_.bin(direction.z())) * layout_.phi_bins;
    add_radiance(buffer, base, block, cos_phi, azimuthal, 1.0);
  }
}

}  // namespace scatterlab
