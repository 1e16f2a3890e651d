#pragma once
// Where photons start and in which direction: at the origin, along a fixed direction (a pencil
// beam, already refracted into the medium where there is a surface) or isotropically (a point
// source, d'Eon & Irving 2011).

#include "scatterlab/core/frame.hpp"
#include "scatterlab/core/random.hpp"

namespace scatterlab {

struct Source {
  Vec3 direction = Vec3::UnitZ();  // of the beam, inside the medium
  bool isotropic = false;          // a point source: direction ignored

  // One Philox call for the point source's direction, none for the beam.
  Vec3 launch(PhotonRandom& random) const {
    if (!isotropic) return direction;
    const auto u = random.next4();
    return isotropic_direction(u[0], u[1]);
  }
};

}  // namespace scatterlab
