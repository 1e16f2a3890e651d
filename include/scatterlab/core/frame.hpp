#pragma once
// Orthonormal frames and direction updates.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "scatterlab/core/azimuth.hpp"
#include "scatterlab/core/phase_function.hpp"

namespace scatterlab {

using Vec3 = Eigen::Vector3d;

// A direction uniform on the unit sphere from two uniforms in (0, 1): cos theta = 2 u - 1.
inline Vec3 isotropic_direction(double u_cos, double u_phi) {
  const double z = 2.0 * u_cos - 1.0;
  const double s = std::sqrt(std::max(0.0, (1.0 - z) * (1.0 + z)));
  const UnitCircle phi = azimuth(u_phi);
  return {s * phi.cos, s * phi.sin, z};
}

// Distance from `p` along unit `w` to the sphere |x| = radius, for p inside it or on it.
inline double distance_to_sphere(const Vec3& p, const Vec3& w, double radius) {
  const double b = p.dot(w);
  const double c = p.squaredNorm() - radius * radius;
  return -b + std::sqrt(std::max(0.0, b * b - c));
}

// Angle between two (not necessarily unit) vectors, accurate near 0 and pi.
inline double angle_between(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// A right-handed orthonormal basis (tangent, bitangent, n) around a unit vector n, following
// Duff et al. 2017, "Building an Orthonormal Basis, Revisited": branch-free apart from the sign
// of n.z, and continuous everywhere except across the plane z = 0, with no loss of precision at
// the poles (the classic Frisvad form breaks at n.z = -1).
struct Frame {
  Vec3 tangent;
  Vec3 bitangent;
  Vec3 normal;

  explicit Frame(const Vec3& n) : normal(n) {
    const double sign = std::copysign(1.0, n.z());
    const double a = -1.0 / (sign + n.z());
    const double b = n.x() * n.y() * a;
    tangent = Vec3(1.0 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
    bitangent = Vec3(b, sign + n.y() * n.y() * a, -n.y());
  }

  Vec3 to_world(double x, double y, double z) const {
    return x * tangent + y * bitangent + z * normal;
  }
};

// The direction at polar angle acos(cos_theta) from `direction` and azimuth phi about it.
// The result is pulled back onto the unit sphere with one Newton step for 1 / |v|,
// v (3 - |v|^2) / 2, exact to rounding since |v| = 1 + O(1e-16): rounding cannot accumulate over
// thousands of events, and the step costs no square root or division on the event's critical
// path.
inline Vec3 scatter_direction(const Vec3& direction, double cos_theta, double cos_phi,
                              double sin_phi) {
  const double sin_theta = std::sqrt(std::max(0.0, (1.0 - cos_theta) * (1.0 + cos_theta)));
  const Vec3 turned =
      Frame(direction).to_world(sin_theta * cos_phi, sin_theta * sin_phi, cos_theta);
  return turned * (0.5 * (3.0 - turned.squaredNorm()));
}

// The direction after scattering by `phase` from `direction`, from two uniforms: cos theta
// from u_cos, the azimuth about the old direction from u_phi.
template <class Phase>
Vec3 scattered_direction(const Phase& phase, const Vec3& direction, double u_cos, double u_phi) {
  const UnitCircle phi = azimuth(u_phi);
  return scatter_direction(direction, phase.sample_cos_theta(u_cos), phi.cos, phi.sin);
}

// Isotropic scattering forgets the old direction: the new one is drawn afresh about +z (the same
// cos theta and azimuth, measured from another axis), with no frame to build and no rotation.
inline Vec3 scattered_direction(const IsotropicPhase& /*phase*/, const Vec3& /*direction*/,
                                double u_cos, double u_phi) {
  return isotropic_direction(u_cos, u_phi);
}

}  // namespace scatterlab
