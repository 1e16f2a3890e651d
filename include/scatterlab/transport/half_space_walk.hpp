#pragma once
// The random walk of one photon in the half-space z > 0 behind a smooth interface of relative
// index eta (Bitterli 2014, §3.2, Alg. 1): exponential free flights of mean 1 mfp, analog
// absorption with probability 1 - albedo at each collision, scattering by the phase function,
// and at the surface an analog choice between leaving (probability 1 - F) and internal
// reflection (probability F), after which the photon flies on for the rest of its sampled path
// (Alg. 1, lines 6-8: the free path is memoryless, so the mirror image of the remainder is a
// valid flight).
//
// Why the analog choice rather than splitting the weight into F reflected and 1 - F leaving:
// every photon then ends in exactly one of exit, absorption or escape with weight 1, so
// per-photon scores are 0 or 1 (times the constant power that entered), the energy balance
// holds photon by photon, and no weight cutoff or roulette is needed to end photons that keep
// reflecting. Splitting would score 1 - F at every hit and so lower the variance of the surface
// tallies somewhat, at the price of a weight carried through every event.
//
// Specialised at compile time on the phase function, on whether the surface has a Fresnel
// interface (eta = 1: no Fresnel arithmetic and no extra random numbers, light simply leaves) and
// on whether the fluence is tallied, so that none of these is a branch in the loop. One Philox
// call per event (free path, absorption, cos theta, azimuth) and one more per surface hit with
// Fresnel (the reflect-or-leave choice); no allocation.

#include <cmath>
#include <cstdint>

#include "scatterlab/core/azimuth.hpp"
#include "scatterlab/core/frame.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/random.hpp"
#include "scatterlab/tally/half_space_scorer.hpp"

namespace scatterlab {

template <class Phase, bool fresnel, bool fluence>
class HalfSpaceWalk {
 public:
  struct Scratch {};  // the surface and collision tallies need no working memory

  // `entry_direction`: the refracted beam direction inside the medium (z component > 0).
  HalfSpaceWalk(const SearchlightSpec& spec, const Phase& phase, const HalfSpaceScorer& scorer,
                const Vec3& entry_direction)
      : phase_(phase),
        scorer_(scorer),
        entry_direction_(entry_direction),
        albedo_(spec.medium.albedo),
        exit_eta_(1.0 / spec.eta),
        escape_radius2_(spec.run.escape_radius * spec.run.escape_radius),
        seed_(spec.run.seed) {}

  Scratch make_scratch() const { return {}; }

  // Transports photons [first, last) into `buffer`; returns the number of scattering events.
  std::uint64_t run(std::uint64_t first, std::uint64_t last, double* buffer, Scratch&) const {
    std::uint64_t scatterings = 0;
    for (std::uint64_t photon = first; photon < last; ++photon) {
      PhotonRandom random(seed_, photon);
      Vec3 position = Vec3::Zero();
      Vec3 direction = entry_direction_;
      for (int order = 0;; ++order) {
        // One Philox call per event: free path, absorption, cos theta, phi.
        const auto u = random.next4();
        const double flight = -std::log(u[0]);
        Vec3 next = position + flight * direction;
        if (next.z() < 0.0) {
          // The flight reaches the surface z = 0 after z / -w_z (Alg. 1, lines 4-5); z >= 0 and
          // next.z < 0 imply w_z < 0.
          const double to_surface = position.z() / -direction.z();
          const double x = position.x() + to_surface * direction.x();
          const double y = position.y() + to_surface * direction.y();
          if constexpr (fresnel) {
            // Leaving the medium the relative index is 1 / eta (fresnel.hpp).
            const FresnelDielectric surface = fresnel_dielectric_terms(-direction.z(), exit_eta_);
            if (!(random.next4()[0] < surface.reflectance())) {
              scorer_.exit(buffer, x, y, surface.cos_transmitted, order);
              break;
            }
            position = Vec3(x, y, 0.0);
            direction.z() = -direction.z();
            next = position + (flight - to_surface) * direction;
          } else {
            scorer_.exit(buffer, x, y, -direction.z(), order);
            break;
          }
        }
        if (next.squaredNorm() > escape_radius2_) {
          scorer_.escape(buffer);
          break;
        }
        position = next;
        if constexpr (fluence) scorer_.collision(buffer, position, order);
        if (u[1] >= albedo_) {
          scorer_.absorption(buffer);
          break;
        }
        const double cos_theta = phase_.sample_cos_theta(u[2]);
        const UnitCircle phi = azimuth(u[3]);
        direction = scatter_direction(direction, cos_theta, phi.cos, phi.sin);
        ++scatterings;
      }
    }
    return scatterings;
  }

 private:
  Phase phase_;
  const HalfSpaceScorer& scorer_;
  Vec3 entry_direction_;
  double albedo_;
  double exit_eta_;
  double escape_radius2_;
  std::uint64_t seed_;
};

}  // namespace scatterlab
