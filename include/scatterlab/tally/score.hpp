#pragma once
// What a tally adds up (OpenMC's scores), and at which event of a photon's walk. Where the
// event falls is the business of the tally's filters (filter.hpp): a score with its filters is a
// tally, and the Scorer (scorer.hpp) has a fixed path for each pair a geometry declares by
// itself, beside the chain that bins any other.

#include <cstddef>
#include <optional>
#include <string_view>

namespace scatterlab {

enum class Score : std::size_t {
  // In the volume, at each collision (weight 1 / sigma_t = 1 mfp) or along each flight (its
  // length), whichever estimator the run uses:
  fluence,   // fixed paths: filters (r, z), or rho
  flux,      // (r, z, component): omega . e_r and omega . e_z
  radiance,  // (r, z, direction)
  // A photon leaves the medium through the surface it entered by (reflectance), or any surface of
  // an object, a count. Fixed paths: no filter (the total), r, (r, theta_o), theta_o, (x, y), a
  // sphere's surface patch, a mesh's triangle.
  exitance,
  // A photon leaves a slab through its far side, a count. Fixed paths: none, r, theta_o,
  // (r, theta_o).
  transmittance,
  // A light's photon is reflected off the surface before it enters, a count.
  entry_reflectance,
  // A photon's weight is absorbed, a count. Fixed paths: none, inside or outside the (r, z)
  // grid, layer, z, (r, z).
  absorbed,
  // The same weight times its depth z: its mean over the absorbed power is the mean depth.
  absorbed_depth,
  // A photon walks past the escape radius, a count.
  escaped,
  // A collision, a count (the fluence's collisions without their 1 mfp): declared tallies only.
  collisions,
  // A photon leaves through the surface it entered by: its weight times the path it travelled
  // since it entered (over the exitance, the mean path of the light leaving: declared tallies
  // only).
  path_length,
  // Known exactly before any photon runs: no buffer cell and no standard error.
  exact,
  count
};

constexpr bool is_volume_score(Score s) {
  return s == Score::fluence || s == Score::flux || s == Score::radiance;
}

// The name a scene gives a score ([[tally]] score = "..."): "fluence", "exitance", ... The
// scores a scene may declare are those of declared_tally.hpp.
std::string_view to_string(Score score);
std::optional<Score> score_named(std::string_view name);

}  // namespace scatterlab
