#pragma once
// Cones of directions (apex at the origin) and boxes of vectors: the bounds with which Walter et
// al. 2009 prune sub-triangles (§3.3.1) and position-normal tree nodes (§3.4).

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/frame.hpp"

namespace scatterlab {

// Angle between two (not necessarily unit) vectors, accurate near 0 and pi.
inline double angle_between(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

struct DirectionCone {
  Vec3 axis = Vec3::UnitZ();
  double half_angle = pi;  // >= pi / 2 is treated as "any direction"

  static DirectionCone everything() { return {Vec3::UnitZ(), pi}; }
  bool is_everything() const { return half_angle >= 0.5 * pi; }
};

// Smallest-axis-is-the-mean cone holding unit directions. A cone of half-angle below pi/2 is
// convex, so it holds every normalised non-negative combination of them: the spherical triangle
// of three corner directions (Walter §3.3.1).
inline DirectionCone cone_of_directions(std::span<const Vec3> directions) {
  Vec3 sum = Vec3::Zero();
  for (const Vec3& d : directions) sum += d;
  const double length = sum.norm();
  if (!(length > 1e-12)) return DirectionCone::everything();
  DirectionCone cone{sum / length, 0.0};
  for (const Vec3& d : directions) {
    cone.half_angle = std::max(cone.half_angle, angle_between(cone.axis, d));
  }
  if (cone.half_angle >= 0.5 * pi) cone.half_angle = pi;
  return cone;
}

// Directions from every point of a ball (center, radius) towards `target`.
inline DirectionCone cone_towards(const Vec3& center, double radius, const Vec3& target) {
  const Vec3 d = target - center;
  const double distance = d.norm();
  if (!(distance > radius)) return DirectionCone::everything();
  return {d / distance, std::asin(radius / distance)};
}

inline DirectionCone merge(const DirectionCone& a, const DirectionCone& b) {
  if (a.is_everything() || b.is_everything()) return DirectionCone::everything();
  const double between = angle_between(a.axis, b.axis);
  if (between + b.half_angle <= a.half_angle) return a;
  if (between + a.half_angle <= b.half_angle) return b;
  const double half = 0.5 * (between + a.half_angle + b.half_angle);
  if (half >= 0.5 * pi) return DirectionCone::everything();
  // Rotate a's axis towards b's by (half - a.half_angle) in their common plane.
  const Vec3 ortho = b.axis - a.axis.dot(b.axis) * a.axis;
  const double ortho_length = ortho.norm();
  if (!(ortho_length > 1e-15)) return {a.axis, half};
  const double turn = half - a.half_angle;
  return {std::cos(turn) * a.axis + std::sin(turn) * (ortho / ortho_length), half};
}

// Two cones share a direction iff the angle between their axes is at most the sum of their
// half-angles (Walter §3.3.1). A small slack covers rounding.
inline bool overlap(const DirectionCone& a, const DirectionCone& b) {
  if (a.is_everything() || b.is_everything()) return true;
  return angle_between(a.axis, b.axis) <= a.half_angle + b.half_angle + 1e-9;
}

struct VectorBox {
  Vec3 lo = Vec3::Constant(-1.0);
  Vec3 hi = Vec3::Constant(1.0);
};

// Per-component bounds of the unit vectors in a cone: the angle to axis e_k lies within
// [alpha_k - theta, alpha_k + theta], clipped to [0, pi].
inline VectorBox box_of_cone(const DirectionCone& cone) {
  VectorBox box;
  if (cone.is_everything()) return box;
  for (int k = 0; k < 3; ++k) {
    const double alpha = std::acos(std::clamp(cone.axis[k], -1.0, 1.0));
    box.lo[k] = std::cos(std::min(pi, alpha + cone.half_angle));
    box.hi[k] = std::cos(std::max(0.0, alpha - cone.half_angle));
  }
  return box;
}

// Cone of the directions of the points of a box; everything if the box holds the origin.
inline DirectionCone cone_of_box(const VectorBox& box) {
  if ((box.lo.array() <= 0.0).all() && (box.hi.array() >= 0.0).all()) {
    return DirectionCone::everything();
  }
  std::array<Vec3, 8> corners;
  for (int c = 0; c < 8; ++c) {
    corners[static_cast<std::size_t>(c)] =
        Vec3((c & 1) ? box.hi.x() : box.lo.x(), (c & 2) ? box.hi.y() : box.lo.y(),
             (c & 4) ? box.hi.z() : box.lo.z());
  }
  const Vec3 center = 0.5 * (box.lo + box.hi);
  DirectionCone cone{center.normalized(), 0.0};
  for (const Vec3& c : corners) cone.half_angle = std::max(cone.half_angle, angle_between(cone.axis, c));
  if (cone.half_angle >= 0.5 * pi) cone.half_angle = pi;
  return cone;
}

// Cone holding the refractive half-vector direction h = eta omega_V + omega_L when omega_V and
// omega_L range over the given cones: bound each by a box, scale and add (Minkowski sum), and
// bound the sum by a cone (Walter §3.3.1).
inline DirectionCone half_vector_cone(const DirectionCone& omega_v, const DirectionCone& omega_l,
                                      double eta) {
  const VectorBox v = box_of_cone(omega_v);
  const VectorBox l = box_of_cone(omega_l);
  return cone_of_box({eta * v.lo + l.lo, eta * v.hi + l.hi});
}

}  // namespace scatterlab
