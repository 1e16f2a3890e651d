#pragma once
// The half-space z > 0 behind a smooth interface of relative index eta = n_medium / n_outside at
// z = 0 (Bitterli 2013, §3.2, Alg. 1). A flight that reaches the surface leaves with probability
// 1 - F and is internally reflected with probability F, after which the photon flies on for the
// rest of its sampled path (Alg. 1, lines 6-8: the free path is memoryless, so the mirror image
// of the remainder is a valid flight).
//
// Why the analog choice rather than splitting the weight into F reflected and 1 - F leaving:
// every photon then ends in exactly one of exit, absorption or escape with weight 1, so
// per-photon scores are 0 or 1, the energy balance holds photon by photon, and no weight cutoff
// or roulette is needed to end photons that keep reflecting. Splitting would score 1 - F at
// every hit and so lower the variance of the surface tallies somewhat, at the price of a weight
// carried through every event.
//
// `fresnel` = false is the index-matched surface (eta = 1): light simply leaves, with no Fresnel
// arithmetic and no extra random numbers. With Fresnel, one more Philox call per surface hit.

#include "scatterlab/core/frame.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/random.hpp"
#include "scatterlab/tally/surface_exit.hpp"

namespace scatterlab {

template <bool fresnel>
class HalfSpace {
 public:
  static constexpr bool has_surface = true;
  static constexpr bool layered = false;

  explicit HalfSpace(double eta) : exit_eta_(1.0 / eta) {}

  // The flight of `flight` mfp from `position` along `direction` ends at `next`. When it crosses
  // the surface, either the photon leaves (returns true, `exit` filled) or it is reflected
  // inside: `position` becomes the point on the surface, `direction` its mirror image and `next`
  // the end of the rest of the flight.
  bool leaves(Vec3& position, Vec3& direction, Vec3& next, double flight, PhotonRandom& random,
              SurfaceExit& exit) const {
    if (!(next.z() < 0.0)) return false;
    // The flight reaches the surface z = 0 after z / -w_z (Alg. 1, lines 4-5); z >= 0 and
    // next.z < 0 imply w_z < 0.
    const double to_surface = position.z() / -direction.z();
    exit.x = position.x() + to_surface * direction.x();
    exit.y = position.y() + to_surface * direction.y();
    exit.remaining = flight - to_surface;
    if constexpr (fresnel) {
      // Leaving the medium the relative index is 1 / eta (fresnel.hpp).
      const FresnelDielectric surface = fresnel_dielectric_terms(-direction.z(), exit_eta_);
      if (!(random.next4()[0] < surface.reflectance())) {
        exit.cos_outside = surface.cos_transmitted;
        return true;
      }
      position = Vec3(exit.x, exit.y, 0.0);
      direction.z() = -direction.z();
      next = position + (flight - to_surface) * direction;
      return false;
    } else {
      exit.cos_outside = -direction.z();
      return true;
    }
  }

 private:
  double exit_eta_;
};

}  // namespace scatterlab
