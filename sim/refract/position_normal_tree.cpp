#include "scatterlab/refract/position_normal_tree.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace scatterlab {
namespace {

constexpr std::uint32_t leaf_size = 2;

std::array<Vec3, 3> corners(const RefractiveTriangle& t) {
  return {t.p0, Vec3(t.p0 + t.edge1), Vec3(t.p0 + t.edge2)};
}

std::array<Vec3, 3> corner_normals(const RefractiveTriangle& t) {
  if (!t.smooth) return {t.geometric_normal, t.geometric_normal, t.geometric_normal};
  return {t.n0.normalized(), Vec3((t.n0 + t.dn1).normalized()), Vec3((t.n0 + t.dn2).normalized())};
}

}  // namespace

PositionNormalTree::PositionNormalTree(const std::vector<RefractiveTriangle>& triangles) {
  order_.resize(triangles.size());
  std::iota(order_.begin(), order_.end(), 0u);
  nodes_.reserve(2 * triangles.size());
  if (!triangles.empty()) build(triangles, 0, static_cast<std::uint32_t>(triangles.size()), 0);
}

// Top-down median split on the widest centroid axis: simpler than Walter's bottom-up
// agglomeration and, with the cone merged bottom-up, gives the same kind of bounds.
std::uint32_t PositionNormalTree::build(const std::vector<RefractiveTriangle>& triangles,
                                        std::uint32_t begin, std::uint32_t end, int depth) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.push_back({});
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  Vec3 centroid_lo = lo, centroid_hi = hi;
  for (std::uint32_t i = begin; i < end; ++i) {
    const auto c = corners(triangles[order_[i]]);
    for (const Vec3& p : c) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const Vec3 centroid = (c[0] + c[1] + c[2]) / 3.0;
    centroid_lo = centroid_lo.cwiseMin(centroid);
    centroid_hi = centroid_hi.cwiseMax(centroid);
  }
  if (end - begin <= leaf_size || depth >= 60) {
    DirectionCone cone;
    bool first = true;
    for (std::uint32_t i = begin; i < end; ++i) {
      const auto n = corner_normals(triangles[order_[i]]);
      const DirectionCone c = cone_of_directions(n);
      cone = first ? c : merge(cone, c);
      first = false;
    }
    nodes_[index] = {lo, hi, cone, begin, end - begin};
    return index;
  }
  int axis = 0;
  (centroid_hi - centroid_lo).maxCoeff(&axis);
  const std::uint32_t middle = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
                   [&](std::uint32_t x, std::uint32_t y) {
                     const auto cx = corners(triangles[x]);
                     const auto cy = corners(triangles[y]);
                     return cx[0][axis] + cx[1][axis] + cx[2][axis] <
                            cy[0][axis] + cy[1][axis] + cy[2][axis];
                   });
  build(triangles, begin, middle, depth + 1);  // the left child is index + 1
  const std::uint32_t right = build(triangles, middle, end, depth + 1);
  nodes_[index] = {lo, hi, merge(nodes_[index + 1].normals, nodes_[right].normals), right, 0};
  return index;
}

bool PositionNormalTree::may_contain_path(const Node& node, const PathQuery& q) {
  const Vec3 center = 0.5 * (node.lo + node.hi);
  const double radius = 0.5 * (node.hi - node.lo).norm();
  const double eta = std::max(q.eta, 1.0 / q.eta);  // the larger index over the smaller
  if (!q.light.at_infinity) {
    // Spindle test (Walter §3.4, eq. 16, Fig. 4): refraction turns a ray by at most
    // pi/2 - asin(1/eta), so the angle VPL is at least pi/2 + asin(1/eta) and, by the inscribed
    // angle theorem, |P - M|^2 + 2 k r <= |L - V|^2 / 4 with M the midpoint, r the distance from
    // the line VL and 2 k = |L - V| |cot(angle)| = |L - V| / sqrt(eta^2 - 1). (Our text's eq. 16
    // prints |L - V| / eta, a weaker bound.)
    const Vec3 middle = 0.5 * (q.v + q.light.position);
    const Vec3 axis = q.light.position - q.v;
    const double chord = axis.norm();
    const Vec3 nearest = middle.cwiseMax(node.lo).cwiseMin(node.hi);
    const double distance2_middle = (nearest - middle).squaredNorm();
    const Vec3 unit_axis = axis / chord;
    const Vec3 offset = center - q.v;
    const double distance_line = (offset - offset.dot(unit_axis) * unit_axis).norm();
    const double r_min = std::max(0.0, distance_line - radius);
    const double quarter = 0.25 * chord * chord * (1.0 + 1e-12);
    if (eta == 1.0) {
      if (r_min > 0.0 || distance2_middle > quarter) return false;
    } else if (distance2_middle + chord / std::sqrt(eta * eta - 1.0) * r_min > quarter) {
      return false;
    }
  }
  if (q.eta == 1.0) return true;  // no half-vector: the spindle is the segment

  const DirectionCone& normals = node.normals;
  const DirectionCone v_cone = cone_towards(center, radius, q.v);
  const DirectionCone l_cone = q.light.at_infinity
                                   ? DirectionCone{q.light.direction_to_light, 0.0}
                                   : cone_towards(center, radius, q.light.position);
  if (!normals.is_everything()) {
    // Sidedness (§3.4): omega_L within 90 degrees of N_s (within the critical angle asin(eta)
    // when eta < 1), -omega_V within the critical angle asin(1/eta) when eta > 1.
    const double max_theta_l = q.eta < 1.0 ? std::asin(q.eta) : 0.5 * pi;
    const double max_theta_v = q.eta > 1.0 ? std::asin(1.0 / q.eta) : 0.5 * pi;
    const double slack = 1e-9;
    if (!l_cone.is_everything() &&
        angle_between(l_cone.axis, normals.axis) - l_cone.half_angle - normals.half_angle >
            max_theta_l + slack) {
      return false;
    }
    if (!v_cone.is_everything() &&
        angle_between(-v_cone.axis, normals.axis) - v_cone.half_angle - normals.half_angle >
            max_theta_v + slack) {
      return false;
    }
  }
  // Cone overlap (§3.4, as §3.3.1 with a box for the positions).
  const DirectionCone h_cone = half_vector_cone(v_cone, l_cone, q.eta);
  return overlap({-q.target_sign * h_cone.axis, h_cone.half_angle}, normals);
}

}  // namespace scatterlab
