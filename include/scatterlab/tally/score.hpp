#pragma once
// What a tally adds up (OpenMC's scores), and at which event of a photon's walk. Where the
// event falls is the business of the tally's filters (filter.hpp); each score is scored by
// Scorer (scorer.hpp) with the filters listed beside it here.

#include <cstddef>

namespace scatterlab {

enum class Score : std::size_t {
  // In the volume, at each collision (weight 1 / sigma_t = 1 mfp) or along each flight (its
  // length), whichever estimator the run uses:
  fluence,            // filters r, z
  flux,               // r, z, component: omega . e_r and omega . e_z
  radiance,           // r, z, direction (theta, phi)
  fluence_spherical,  // rho
  // Where a photon leaves the medium through its surface, a count:
  exit,                 // no filter: the total
  exit_by_radius,       // r
  exit_radiance,        // r, exit angle theta_o
  exit_by_polar_angle,  // on a sphere: psi (the angle from the lit pole) and the azimuth
  exit_by_triangle,     // on a triangle mesh: the triangle it leaves through
  exit_by_position,     // on a plane: x, y (about the entry point)
  exit_by_angle,        // exit angle theta_o, wherever on the surface
  // Where a photon leaves a slab through its far side (transmitted), a count; the side it
  // entered is the exit scores above:
  transmitted,                  // no filter: the total
  transmitted_by_radius,        // r
  transmitted_by_angle,         // theta_o, from the far side's outward normal
  transmitted_by_radius_angle,  // r, theta_o
  // Where a light's photon is reflected off the surface before entering (a sphere light), a
  // count:
  reflected_at_entry,
  // Where a photon's walk ends, a count (or, for the depth, z):
  absorbed,                  // anywhere
  absorbed_in_grid,          // inside the (r, z) grid
  absorbed_outside_grid,     // outside it
  absorption_depth,          // z at absorption: its mean is the mean absorption depth
  absorbed_by_layer,         // a slab's layer
  absorbed_by_depth,         // z
  absorbed_by_radius_depth,  // r, z
  escaped,                   // past the escape radius
  // Known exactly before any photon runs: no buffer cell and no standard error.
  exact,
  count
};

constexpr bool is_volume_score(Score s) {
  return s == Score::fluence || s == Score::flux || s == Score::radiance ||
         s == Score::fluence_spherical;
}

}  // namespace scatterlab
