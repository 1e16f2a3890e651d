#pragma once
// The axes the filters of a run bin along; a run sets those its tallies use.
//
// Frames: a point is (r, z) about the beam axis; a direction is (theta, phi) with theta from +z
// and phi from the outward radial direction e_r of the point, towards e_phi = z x e_r. Unfolded
// phi bins cover [0, 2 pi) and need an even count, so that the bins of phi and 2 pi - phi mirror
// each other; folded bins cover [0, pi]. The exit angle theta_o is measured outside the medium
// from the outward normal of its surface.

#include "scatterlab/tally/axis.hpp"

namespace scatterlab {

struct TallyAxes {
  UniformAxis r;      // distance from the beam axis, mfp
  UniformAxis z;      // depth along the beam axis, mfp
  UniformAxis theta;  // direction: polar angle from +z
  UniformAxis phi;    // direction: azimuth from e_r
  bool fold_phi = false;
  UniformAxis rho;      // distance from the source, mfp
  UniformAxis theta_o;  // exit angle, outside the medium
  UniformAxis psi;      // on a sphere: the exit point's polar angle from the lit pole
  UniformAxis azimuth;  // on a sphere: the exit point's azimuth about z, from +x, over [0, 2 pi)
  UniformAxis x, y;     // on a plane: the exit point about the entry point
};

}  // namespace scatterlab
