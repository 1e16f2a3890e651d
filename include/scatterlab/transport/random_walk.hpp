#pragma once
// The random walk of one photon, for every geometry (Vavassori §4.1; Bitterli 2013, Alg. 1):
// exponential free flights of mean 1 mfp, analog absorption with probability 1 - albedo at each
// collision (so the number of collisions is geometric, §4.1), scattering by the phase function,
// and whatever the geometry does where a flight meets its surface.
//
// Specialised at compile time on the geometry (infinite_medium.hpp, half_space.hpp, sphere.hpp),
// the phase function and the volume estimator, so that the loop holds no isotropic/HG branch, no
// collision/track-length branch, and no boundary code where the geometry has no surface. One
// Philox call per event (free path, absorption, cos theta, azimuth); no allocation.
//
// A geometry provides `static constexpr bool has_surface` and, when it has one,
//   bool leaves(Vec3& position, Vec3& direction, Vec3& next, double flight, PhotonRandom&,
//               SurfaceExit&) const;
// which moves a flight that meets the surface and says whether the photon left through it.

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "scatterlab/core/azimuth.hpp"
#include "scatterlab/core/frame.hpp"
#include "scatterlab/core/random.hpp"
#include "scatterlab/tally/scorer.hpp"
#include "scatterlab/tally/surface_exit.hpp"
#include "scatterlab/transport/source.hpp"

namespace scatterlab {

// How the volume tallies are scored: at each collision, along each flight, or not at all (a
// run with surface tallies alone).
enum class VolumeEstimator { none, collision, track_length };

template <class Geometry, class Phase, VolumeEstimator estimator>
class RandomWalk {
  // A flight that is bent at a surface is not one straight track.
  static_assert(!(Geometry::has_surface && estimator == VolumeEstimator::track_length),
                "the track-length estimator needs a geometry without a surface");

 public:
  // `escape_radius`: photons farther than this from the origin are stopped and counted as
  // escaped (infinity for none).
  RandomWalk(const Geometry& geometry, const Phase& phase, const Source& source,
             const Scorer& scorer, double albedo, double escape_radius, std::uint64_t seed)
      : geometry_(geometry),
        phase_(phase),
        source_(source),
        scorer_(scorer),
        albedo_(albedo),
        escape_radius_(escape_radius),
        escape_radius2_(escape_radius * escape_radius),
        seed_(seed) {}

  // Working memory of the track-length estimator's bin crossings, one per thread.
  std::vector<double> make_scratch() const {
    if constexpr (estimator == VolumeEstimator::track_length)
      return scorer_.make_crossing_scratch();
    return {};
  }

  // Transports photons [first, last) into `buffer`; returns the number of scattering events.
  std::uint64_t run(std::uint64_t first, std::uint64_t last, double* buffer,
                    std::vector<double>& crossings) const {
    std::uint64_t scatterings = 0;
    for (std::uint64_t photon = first; photon < last; ++photon) {
      PhotonRandom random(seed_, photon);
      Vec3 position = Vec3::Zero(), direction = Vec3::UnitZ();
      if (!source_.launch(random, position, direction)) {
        scorer_.reflection_at_entry(buffer);
        continue;
      }
      for (int order = 0;; ++order) {
        // One Philox call per event: free path, absorption, cos theta, phi.
        const auto u = random.next4();
        const double flight = -std::log(u[0]);
        Vec3 next = position + flight * direction;
        if constexpr (Geometry::has_surface) {
          SurfaceExit exit;
          if (geometry_.leaves(position, direction, next, flight, random, exit)) {
            scorer_.exit(buffer, exit, order);
            break;
          }
        }
        if (next.squaredNorm() > escape_radius2_) {
          if constexpr (estimator == VolumeEstimator::track_length) {
            scorer_.flight(buffer, crossings, position, direction,
                           distance_to_sphere(position, direction, escape_radius_), order);
          }
          scorer_.escape(buffer);
          break;
        }
        if constexpr (estimator == VolumeEstimator::track_length) {
          scorer_.flight(buffer, crossings, position, direction, flight, order);
        }
        position = next;
        if constexpr (estimator == VolumeEstimator::collision) {
          scorer_.collision(buffer, position, direction, order);
        }
        if (u[1] >= albedo_) {
          scorer_.absorption(buffer, position, order);
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
  Geometry geometry_;
  Phase phase_;
  Source source_;
  const Scorer& scorer_;
  double albedo_;
  double escape_radius_;
  double escape_radius2_;
  std::uint64_t seed_;
};

}  // namespace scatterlab
