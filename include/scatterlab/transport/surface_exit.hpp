#pragma once
// Where and how a photon left the medium through its surface: what the surface tallies bin.

namespace scatterlab {

struct SurfaceExit {
  double x = 0.0, y = 0.0;   // on the surface, about the entry point
  double cos_outside = 1.0;  // from the outward normal, outside (after refraction)
};

}  // namespace scatterlab
