#pragma once
// Where and how a photon left the medium through its surface: what the surface tallies bin.

#include <cstdint>

namespace scatterlab {

struct SurfaceExit {
  double x = 0.0, y = 0.0;     // on the surface, about the entry point (the beam axis)
  double cos_outside = 1.0;    // from the outward normal, outside (after refraction)
  double cos_polar = 1.0;      // on a sphere: cos psi, psi the angle from the lit pole (sphere.hpp)
  bool transmitted = false;    // left a slab through its far side (slab.hpp), not the lit one
  std::uint32_t triangle = 0;  // on a triangle mesh: the triangle it left through
  // The part of the last flight not travelled, past the point where the photon left (mfp): the
  // walk's clock stops at the surface (random_walk.hpp). A layered geometry keeps its own clock.
  double remaining = 0.0;
};

}  // namespace scatterlab
