#pragma once
// The random walk of one photon in an infinite homogeneous medium (Vavassori §4.1): exponential
// free flights of mean 1 mfp, analog absorption with probability 1 - albedo at each collision
// (so the number of collisions is geometric, §4.1), and scattering by the phase function.
//
// Specialised at compile time on the phase function and the estimator, so that the loop holds
// neither an isotropic/HG branch nor a collision/track-length branch; it has no boundary code.

#include <cmath>
#include <cstdint>
#include <vector>

#include "scatterlab/core/azimuth.hpp"
#include "scatterlab/core/frame.hpp"
#include "scatterlab/core/random.hpp"
#include "scatterlab/tally/scorer.hpp"
#include "scatterlab/transport/simulation.hpp"

namespace scatterlab {

inline Vec3 isotropic_direction(double u_cos, double u_phi) {
  const double z = 2.0 * u_cos - 1.0;
  const double s = std::sqrt(std::max(0.0, (1.0 - z) * (1.0 + z)));
  const UnitCircle phi = azimuth(u_phi);
  return {s * phi.cos, s * phi.sin, z};
}

// Distance from `p` along unit `w` to the sphere |x| = radius, for p inside it.
inline double distance_to_sphere(const Vec3& p, const Vec3& w, double radius) {
  const double b = p.dot(w);
  const double c = p.squaredNorm() - radius * radius;
  return -b + std::sqrt(std::max(0.0, b * b - c));
}

template <class Phase, Estimator estimator>
class RandomWalk {
 public:
  RandomWalk(const SimulationSpec& spec, const Phase& phase, const Scorer& scorer)
      : phase_(phase),
        scorer_(scorer),
        albedo_(spec.medium.albedo),
        escape_radius_(spec.run.escape_radius),
        escape_radius2_(spec.run.escape_radius * spec.run.escape_radius),
        seed_(spec.run.seed),
        point_source_(spec.source == SourceKind::point) {}

  // Working memory of the track-length estimator's bin crossings, one per thread.
  std::vector<double> make_scratch() const { return scorer_.make_crossing_scratch(); }

  // Transports photons [first, last) into `buffer`; returns the number of scattering events.
  std::uint64_t run(std::uint64_t first, std::uint64_t last, double* buffer,
                    std::vector<double>& crossings) const {
    std::uint64_t scatterings = 0;
    for (std::uint64_t photon = first; photon < last; ++photon) {
      PhotonRandom random(seed_, photon);
      Vec3 position = Vec3::Zero();
      Vec3 direction = Vec3::UnitZ();
      if (point_source_) {
        const auto u = random.next4();
        direction = isotropic_direction(u[0], u[1]);
      }
      for (int order = 0;; ++order) {
        // One Philox call per event: free path, absorption, cos theta, phi.
        const auto u = random.next4();
        const double flight = -std::log(u[0]);
        const Vec3 next = position + flight * direction;
        if (next.squaredNorm() > escape_radius2_) {
          if constexpr (estimator == Estimator::track_length) {
            scorer_.flight(buffer, crossings, position, direction,
                           distance_to_sphere(position, direction, escape_radius_), order);
          }
          scorer_.escape(buffer);
          break;
        }
        if constexpr (estimator == Estimator::track_length) {
          scorer_.flight(buffer, crossings, position, direction, flight, order);
        }
        position = next;
        if constexpr (estimator == Estimator::collision) {
          scorer_.collision(buffer, position, direction, order);
        }
        if (u[1] >= albedo_) {
          scorer_.absorption(buffer, position);
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
  const Scorer& scorer_;
  double albedo_;
  double escape_radius_;
  double escape_radius2_;
  std::uint64_t seed_;
  bool point_source_;
};

}  // namespace scatterlab
