#pragma once
// The random walk of one photon, for every geometry (Vavassori §4.1; Bitterli 2013, Alg. 1):
// exponential free flights of mean 1 mfp, analog absorption with probability 1 - albedo at each
// collision (so the number of collisions is geometric, §4.1), scattering by the phase function,
// and whatever the geometry does where a flight meets its surface.
//
// Specialised at compile time on the geometry (infinite_medium.hpp, half_space.hpp, sphere.hpp,
// slab.hpp; a triangle mesh, mesh/mesh_boundary.hpp), the light, the phase function, the volume
// estimator and the weighting (weighting.hpp), so that the loop holds no isotropic/HG branch, no
// collision/track-length branch, no boundary code where the geometry has no surface and no weight
// where absorption is analog. One Philox call per event (free path, absorption or roulette, cos
// theta, azimuth); no allocation.
//
// A geometry provides `static constexpr bool has_surface` and `layered`. A homogeneous one with a
// surface provides
//   bool leaves(Vec3& position, Vec3& direction, Vec3& next, double flight, PhotonRandom&,
//               SurfaceExit&) const;
// which moves a flight (in mfp) that meets the surface and says whether the photon left through
// it. A layered one holds its own media (the walk's albedo and phase function are unused) and
// provides layer_of, albedo(layer), sample_cos_theta(layer, xi) and
//   bool leaves(Vec3& position, Vec3& direction, int& layer, double optical, PhotonRandom&,
//               SurfaceExit&) const;
// which spends a free path of `optical` optical depths through its layers.
//
// `chained`: the run has tallies whose filters bin events themselves (the Scorer's chain, among
// them time of flight), and the walk keeps the path each photon has travelled since it entered:
// in mfp in a homogeneous geometry (its flights, the last one to the surface: SurfaceExit's
// remaining), and in a slab the length times each layer's index (slab.hpp). A run without them
// compiles none of it.

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "scatterlab/core/azimuth.hpp"
#include "scatterlab/core/frame.hpp"
#include "scatterlab/core/random.hpp"
#include "scatterlab/tally/scorer.hpp"
#include "scatterlab/tally/surface_exit.hpp"
#include "scatterlab/transport/estimator.hpp"
#include "scatterlab/transport/source.hpp"
#include "scatterlab/transport/weighting.hpp"

namespace scatterlab {

// `Light` launches each photon (Source, or a light that knows its geometry: kernel.hpp).
template <class Geometry, class Phase, Estimator estimator, Weighting weighting = Weighting::analog,
          class Light = Source, bool chained = false>
class RandomWalk {
  // A flight that is bent at a surface is not one straight track.
  static_assert(!(Geometry::has_surface && estimator == Estimator::track_length),
                "the track-length estimator needs a geometry without a surface");
  // Layers are scored at their events alone (absorption, exit).
  static_assert(!(Geometry::layered && estimator != Estimator::none),
                "a layered geometry has no volume estimator");
  // A chained fluence is scored at collisions.
  static_assert(!(chained && estimator == Estimator::track_length),
                "chained tallies take the collision estimator");

 public:
  // `escape_radius`: photons farther than this from the origin are stopped and counted as
  // escaped (infinity for none).
  RandomWalk(const Geometry& geometry, const Phase& phase, const Light& source,
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
    if constexpr (estimator == Estimator::track_length)
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
      // Constant 1 under analog absorption, where the compiler folds it away.
      double weight = 1.0;
      double path = 0.0;  // chained only: travelled since the photon entered
      int layer = 0;
      if constexpr (Geometry::layered) layer = geometry_.layer_of(position, direction);
      for (int order = 0;; ++order) {
        // One Philox call per event: free path, absorption (or roulette), cos theta, phi.
        const auto u = random.next4();
        const double flight = -std::log(u[0]);  // mfp, or optical depth in layers
        Vec3 next;
        if constexpr (Geometry::layered) {
          SurfaceExit exit;
          if (geometry_.template leaves<chained>(position, direction, layer, flight, random, exit,
                                                 &path)) {
            scorer_.exit(buffer, exit, order, weight);
            if constexpr (chained) {
              scorer_.chained_exit(buffer, exit, direction, path, order, weight);
            }
            break;
          }
          next = position;
        } else {
          next = position + flight * direction;
          if constexpr (Geometry::has_surface) {
            SurfaceExit exit;
            if (geometry_.leaves(position, direction, next, flight, random, exit)) {
              scorer_.exit(buffer, exit, order, weight);
              if constexpr (chained) {
                scorer_.chained_exit(buffer, exit, direction, path + (flight - exit.remaining),
                                     order, weight);
              }
              break;
            }
          }
          if constexpr (chained) path += flight;
        }
        if (next.squaredNorm() > escape_radius2_) {
          if constexpr (estimator == Estimator::track_length) {
            scorer_.flight(buffer, crossings, position, direction,
                           distance_to_sphere(position, direction, escape_radius_), order);
          }
          scorer_.escape(buffer, weight);
          break;
        }
        if constexpr (estimator == Estimator::track_length) {
          scorer_.flight(buffer, crossings, position, direction, flight, order);
        }
        position = next;
        if constexpr (estimator == Estimator::collision) {
          scorer_.collision(buffer, position, direction, order);
          if constexpr (chained) {
            scorer_.chained_collision(buffer, position, direction, path, order);
          }
        }
        double albedo = albedo_;
        if constexpr (Geometry::layered) albedo = geometry_.albedo(layer);
        if constexpr (weighting == Weighting::implicit_capture) {
          // MCML's drop and roulette (weighting.hpp): deposit the absorbed part of the weight;
          // below the threshold, survive with probability roulette_chance at 1 / roulette_chance
          // times the weight, with u[1], which absorption no longer needs.
          const double deposited = weight * (1.0 - albedo);
          scorer_.absorption(buffer, position, order, layer, deposited);
          if constexpr (chained)
            scorer_.chained_absorption(buffer, position, direction, path, order, layer, deposited);
          weight -= deposited;
          if (weight < roulette_threshold) {
            if (!(weight > 0.0) || u[1] >= roulette_chance) break;
            weight /= roulette_chance;
          }
        } else if (u[1] >= albedo) {
          scorer_.absorption(buffer, position, order, layer);
          if constexpr (chained)
            scorer_.chained_absorption(buffer, position, direction, path, order, layer, 1.0);
          break;
        }
        if constexpr (Geometry::layered) {
          const UnitCircle phi = azimuth(u[3]);
          direction = scatter_direction(direction, geometry_.sample_cos_theta(layer, u[2]), phi.cos,
                                        phi.sin);
        } else {
          direction = scattered_direction(phase_, direction, u[2], u[3]);
        }
        ++scatterings;
      }
    }
    return scatterings;
  }

 private:
  Geometry geometry_;
  Phase phase_;
  Light source_;
  const Scorer& scorer_;
  double albedo_;
  double escape_radius_;
  double escape_radius2_;
  std::uint64_t seed_;
};

}  // namespace scatterlab
