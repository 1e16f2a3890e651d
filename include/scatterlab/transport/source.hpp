#pragma once
// Where photons start and in which direction:
//   beam          a pencil beam from `position` along `direction` (already refracted into the
//                 medium where there is a surface);
//   point         an isotropic point source at `position` (d'Eon & Irving 2011);
//   sphere_light  a directional light travelling along +z onto the sphere of radius R about the
//                 origin (Bitterli 2013, §3.2, the lit sphere): photons arrive uniformly over the
//                 sphere's shadow disk, meet the surface at cos theta_i = sqrt(1 - b^2 / R^2) for
//                 impact parameter b, and are reflected there with probability F(cos theta_i)
//                 (the analog choice of half_space.hpp) or refracted in.

#include <algorithm>
#include <cmath>

#include "scatterlab/core/azimuth.hpp"
#include "scatterlab/core/frame.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/random.hpp"

namespace scatterlab {

struct Source {
  enum class Kind { beam, point, sphere_light };
  Kind kind = Kind::beam;
  Vec3 position = Vec3::Zero();    // beam and point
  Vec3 direction = Vec3::UnitZ();  // beam, inside the medium
  double sphere_radius = 1.0;      // sphere_light, mfp
  double eta = 1.0;                // sphere_light: n_medium / n_outside

  // A photon's start. The beam draws no random number, the point source and the sphere light
  // one Philox call. False when a sphere light's photon is reflected off the surface and never
  // enters.
  bool launch(PhotonRandom& random, Vec3& start, Vec3& heading) const {
    switch (kind) {
      case Kind::beam:
        start = position;
        heading = direction;
        return true;
      case Kind::point: {
        const auto u = random.next4();
        start = position;
        heading = isotropic_direction(u[0], u[1]);
        return true;
      }
      case Kind::sphere_light:
        return enter_sphere(random.next4(), start, heading);
    }
    return false;
  }

 private:
  // b^2 = R^2 u uniform over the disk; the entry point on the lit hemisphere z < 0.
  bool enter_sphere(const std::array<double, 4>& u, Vec3& start, Vec3& heading) const {
    const double b2 = u[0];  // (b / R)^2
    const double cos_incident = std::sqrt(std::max(0.0, 1.0 - b2));
    const UnitCircle phi = azimuth(u[1]);
    const double b = sphere_radius * std::sqrt(b2);
    start = Vec3(b * phi.cos, b * phi.sin, -sphere_radius * cos_incident);
    const FresnelDielectric surface = fresnel_dielectric_terms(cos_incident, eta);
    if (u[2] < surface.reflectance()) return false;
    const Vec3 outward = start / sphere_radius;
    refract(Vec3::UnitZ(), outward, eta, heading);
    return true;
  }
};

}  // namespace scatterlab
