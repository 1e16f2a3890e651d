#pragma once
// Cones of directions (apex at the origin) and boxes of vectors: the bounds with which Walter et
// al. 2009 prune sub-triangles (§3.3.1) and position-normal tree nodes (§3.4).

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <span>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/frame.hpp"

namespace scatterlab {

// Choosing the widest direction by its cosine can miss by a rounding tie: cosines equal to 1e-16
// differ in angle by at most about 1e-8 (at angle 0), which this slack covers.
constexpr double cosine_tie_slack = 2e-8;

struct DirectionCone {
  Vec3 axis = Vec3::UnitZ();
  double half_angle = pi;  // >= pi / 2 is treated as "any direction"

  static DirectionCone everything() { return {Vec3::UnitZ(), pi}; }
  static DirectionCone none() { return {Vec3::UnitZ(), -1.0}; }  // holds no direction
  bool is_everything() const { return half_angle >= 0.5 * pi; }
  bool is_none() const { return half_angle < 0.0; }
};

// The axis of cone_of_directions, the mean of the unit directions, and the direction widest
// from it (the least cosine); nullopt where the mean vanishes.
struct MeanDirection {
  Vec3 axis;
  const Vec3* widest;
};
inline std::optional<MeanDirection> mean_direction(std::span<const Vec3> directions) {
  Vec3 sum = Vec3::Zero();
  for (const Vec3& d : directions) sum += d;
  const double length = sum.norm();
  if (!(length > 1e-12)) return std::nullopt;
  MeanDirection mean{sum / length, &directions.front()};
  for (const Vec3& d : directions) {
    if (mean.axis.dot(d) < mean.axis.dot(*mean.widest)) mean.widest = &d;
  }
  return mean;
}

// Smallest-axis-is-the-mean cone holding unit directions. A cone of half-angle below pi/2 is
// convex, so it holds every normalised non-negative combination of them: the spherical triangle
// of three corner directions (Walter §3.3.1).
inline DirectionCone cone_of_directions(std::span<const Vec3> directions) {
  const auto mean = mean_direction(directions);
  if (!mean) return DirectionCone::everything();
  // One accurate angle for the widest direction, not one per direction.
  DirectionCone cone{mean->axis, angle_between(mean->axis, *mean->widest) + cosine_tie_slack};
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
  if (a.is_none() || b.is_none()) return false;
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
  // cos(alpha -+ theta) expanded, with alpha = acos(axis_k): no per-component trig. The clips
  // alpha - theta <= 0 and alpha + theta >= pi compare cosines (cos decreases on [0, pi]); the
  // box is widened by rounding slack so that it stays a bound.
  const double cos_t = std::cos(cone.half_angle), sin_t = std::sin(cone.half_angle);
  constexpr double slack = 1e-12;
  for (int k = 0; k < 3; ++k) {
    const double cos_a = std::clamp(cone.axis[k], -1.0, 1.0);
    const double sin_a = std::sqrt(std::max(0.0, 1.0 - cos_a * cos_a));
    box.lo[k] = cos_a <= -cos_t ? -1.0 : std::max(-1.0, cos_a * cos_t - sin_a * sin_t - slack);
    box.hi[k] = cos_a >= cos_t ? 1.0 : std::min(1.0, cos_a * cos_t + sin_a * sin_t + slack);
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
  // The widest corner has the least cosine to the axis (as in cone_of_directions).
  std::size_t widest = 0;
  double least = 2.0;
  for (std::size_t c = 0; c < corners.size(); ++c) {
    const double cosine = cone.axis.dot(corners[c]) / corners[c].norm();
    if (cosine < least) {
      least = cosine;
      widest = c;
    }
  }
  cone.half_angle = angle_between(cone.axis, corners[widest]) + cosine_tie_slack;
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

// Cone holding the direction t in which light travels after refracting into the medium (index
// ratio eta = n_inside / n_outside), when it arrives from directions in l_cone (towards the
// light) through shading normals in `normals` (facing the light's side); none() when no light
// enters there (behind every normal, or totally reflected). Snell in vector form (pbrt-v4,
// Refract): eta t = -omega_L + k n with k = cos_i - eta cos_t. The range of cos_i (from the
// angle between the cones) bounds cos_t (increasing in cos_i) and so k, and interval arithmetic
// on boxes bounds -omega_L + k n. Unlike half_vector_cone it does not involve V, so it can be
// computed once per light.
inline DirectionCone refracted_cone(const DirectionCone& normals, const DirectionCone& l_cone,
                                    double eta) {
  if (normals.is_everything() || l_cone.is_everything()) return DirectionCone::everything();
  const double between = angle_between(l_cone.axis, normals.axis);
  const double theta_min = std::max(0.0, between - l_cone.half_angle - normals.half_angle);
  const double theta_max = between + l_cone.half_angle + normals.half_angle;
  if (theta_min >= 0.5 * pi) return DirectionCone::none();
  constexpr double slack = 1e-12;
  double cos_lo = theta_max >= 0.5 * pi ? 0.0 : std::cos(theta_max) - slack;
  const double cos_hi = std::min(1.0, std::cos(theta_min) + slack);
  if (eta < 1.0) {  // total internal reflection below the critical cosine
    const double cos_critical = std::sqrt(1.0 - eta * eta);
    if (cos_hi <= cos_critical) return DirectionCone::none();
    cos_lo = std::max(cos_lo, cos_critical);
  }
  const auto cos_t = [eta](double cos_i) {
    return std::sqrt(std::max(0.0, 1.0 - (1.0 - cos_i * cos_i) / (eta * eta)));
  };
  const double k_lo = cos_lo - eta * cos_t(cos_hi), k_hi = cos_hi - eta * cos_t(cos_lo);
  const VectorBox n = box_of_cone(normals);
  const VectorBox l = box_of_cone(l_cone);
  VectorBox t;
  for (int c = 0; c < 3; ++c) {
    const std::array<double, 4> kn{k_lo * n.lo[c], k_lo * n.hi[c], k_hi * n.lo[c], k_hi * n.hi[c]};
    t.lo[c] = -l.hi[c] + *std::min_element(kn.begin(), kn.end()) - slack;
    t.hi[c] = -l.lo[c] + *std::max_element(kn.begin(), kn.end()) + slack;
  }
  return cone_of_box(t);
}

}  // namespace scatterlab
