#pragma once
// A sphere of radius R about the origin, filled with the medium, behind a smooth interface of
// relative index eta = n_medium / n_outside (Bitterli 2013, §3.2: the lit sphere; Vavassori
// §4.3). As at the half-space's surface (half_space.hpp), a flight that reaches the surface
// leaves with probability 1 - F(cos theta_i) and is reflected inside with probability F, and the
// photon flies on for the rest of its sampled path (the free path is memoryless). On a sphere the
// reflected remainder can reach the surface again, after a chord of 2 R cos theta_i, at the same
// angle of incidence: the reflections repeat until the flight ends inside or the photon leaves.
//
// Under total internal reflection (eta > 1, beyond the critical angle) every hit of a flight is
// at the same angle and reflected: the whole chords are taken as one rotation about the centre.
//
// The exit point is reported as the cosine of its polar angle psi from the lit pole, the point
// (0, 0, -R) that faces light travelling along +z (cos psi = -z / R), and as (x, y).
//
// `fresnel` = false is the index-matched sphere (eta = 1): light simply leaves.

#include <algorithm>
#include <cmath>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/frame.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/random.hpp"
#include "scatterlab/tally/surface_exit.hpp"

namespace scatterlab {

template <bool fresnel>
class Sphere {
 public:
  static constexpr bool has_surface = true;
  static constexpr bool layered = false;

  Sphere(double radius, double eta)
      : radius_(radius), radius2_(radius * radius), exit_eta_(1.0 / eta) {}

  // The flight of `flight` mfp from `position` along `direction` ends at `next`. When it crosses
  // the surface, either the photon leaves (returns true, `exit` filled) or it is reflected
  // inside, as often as the rest of the flight meets the surface again: `position` becomes the
  // last point of reflection, `direction` the reflected direction and `next` the end of the
  // flight.
  bool leaves(Vec3& position, Vec3& direction, Vec3& next, double flight, PhotonRandom& random,
              SurfaceExit& exit) const {
    while (next.squaredNorm() > radius2_) {
      const double to_surface = distance_to_sphere(position, direction, radius_);
      const Vec3 hit = position + to_surface * direction;
      const Vec3 normal = hit / radius_;
      const double cos_inside = std::clamp(direction.dot(normal), 0.0, 1.0);
      exit.x = hit.x();
      exit.y = hit.y();
      exit.cos_polar = std::clamp(-hit.z() / radius_, -1.0, 1.0);
      exit.remaining = flight - to_surface;
      if constexpr (fresnel) {
        const FresnelDielectric surface = fresnel_dielectric_terms(cos_inside, exit_eta_);
        // A flight exactly tangent to the surface (cos 0, probability 0) would be reflected
        // into itself for ever: it leaves.
        if (!(cos_inside > 0.0)) {
          exit.cos_outside = surface.cos_transmitted;
          return true;
        }
        flight -= to_surface;
        const Vec3 reflected = (direction - 2.0 * cos_inside * normal).normalized();
        if (surface.total_internal_reflection) {
          // Every later hit of this flight is at the same angle, so totally reflected too:
          // each whole chord (2 R cos theta_i) it still covers turns the photon about the
          // centre by pi - 2 theta_i, in the plane of the hit and the direction. One rotation
          // for all of them, where a loop would count 1 / cos theta_i bounces per mfp near
          // grazing incidence; no random number is drawn (F = 1).
          const double chord = 2.0 * radius_ * cos_inside;
          const double chords = std::floor(flight / chord);
          position = hit;
          direction = reflected;
          if (chords >= 1.0) {
            const double turn = chords * (pi - 2.0 * std::acos(cos_inside));
            const Eigen::AngleAxisd rotation(turn, hit.cross(reflected).normalized());
            position = rotation * hit;
            direction = (rotation * reflected).normalized();
            flight -= chords * chord;
          }
          next = position + flight * direction;
          continue;
        }
        if (!(random.next4()[0] < surface.reflectance())) {
          exit.cos_outside = surface.cos_transmitted;
          return true;
        }
        position = hit;
        direction = reflected;
        next = position + flight * direction;
      } else {
        exit.cos_outside = cos_inside;
        return true;
      }
    }
    return false;
  }

  double radius() const { return radius_; }

 private:
  double radius_, radius2_;
  double exit_eta_;
};

}  // namespace scatterlab
