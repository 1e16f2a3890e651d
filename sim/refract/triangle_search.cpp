#include "scatterlab/refract/triangle_search.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "scatterlab/refract/bounding_cone.hpp"

namespace scatterlab {
namespace {

using Vec2 = Eigen::Vector2d;
using Jacobian = Eigen::Matrix<double, 3, 2>;

// Derivative of v / |v| along dv: (dv - (u . dv) u) / |v| with u = v / |v| (Walter eq. 10).
Vec3 unit_derivative(const Vec3& unit, double length, const Vec3& dv) {
  return (dv - unit.dot(dv) * unit) / length;
}

IntervalVec3 interval_unit_derivative(const IntervalVec3& unit, Interval inverse_length,
                                      const IntervalVec3& dv) {
  return inverse_length * (dv - dot(unit, dv) * unit);
}

}  // namespace

RefractiveTriangle RefractiveTriangle::from_mesh(const TriangleMesh& mesh, std::size_t t) {
  RefractiveTriangle tri;
  tri.p0 = mesh.vertex(t, 0);
  tri.edge1 = mesh.vertex(t, 1) - tri.p0;
  tri.edge2 = mesh.vertex(t, 2) - tri.p0;
  tri.geometric_normal = mesh.geometric_normal(t);
  tri.index = static_cast<std::uint32_t>(t);
  tri.smooth = mesh.has_shading_normals();
  if (tri.smooth) {
    tri.n0 = mesh.corner_normal(t, 0);
    tri.dn1 = mesh.corner_normal(t, 1) - tri.n0;
    tri.dn2 = mesh.corner_normal(t, 2) - tri.n0;
    // Interpolating three equal normals gives the plain 1D problem.
    if (tri.dn1.squaredNorm() + tri.dn2.squaredNorm() == 0.0 &&
        (tri.n0 - tri.geometric_normal).squaredNorm() < 1e-30) {
      tri.smooth = false;
    }
  } else {
    tri.n0 = tri.geometric_normal;
    tri.dn1 = tri.dn2 = Vec3::Zero();
  }
  return tri;
}

Eigen::Vector2d RefractiveTriangle::barycentric(const Vec3& p) const {
  const Vec3 d = p - p0;
  const double e11 = edge1.dot(edge1), e12 = edge1.dot(edge2), e22 = edge2.dot(edge2);
  const double det = e11 * e22 - e12 * e12;
  const double d1 = edge1.dot(d), d2 = edge2.dot(d);
  if (!(std::abs(det) > 0.0)) return Vec2::Constant(std::numeric_limits<double>::quiet_NaN());
  return {(e22 * d1 - e12 * d2) / det, (e11 * d2 - e12 * d1) / det};
}

Residual evaluate_residual(const RefractiveTriangle& tri, const PathQuery& q, double a, double b) {
  const Vec3 p = tri.point(a, b);
  const Vec3 to_v = q.v - p;
  const double length_v = to_v.norm();
  const Vec3 omega_v = to_v / length_v;  // Walter eq. 1
  Vec3 omega_l;
  double length_l = 0.0;
  if (q.light.at_infinity) {
    omega_l = q.light.direction_to_light;
  } else {
    const Vec3 to_l = q.light.position - p;
    length_l = to_l.norm();
    omega_l = to_l / length_l;  // eq. 2
  }
  const Vec3 h = q.eta * omega_v + omega_l;  // eq. 3, unnormalised
  const double length_h = h.norm();
  const Vec3 h_unit = h / length_h;
  const Vec3 n = tri.n0 + a * tri.dn1 + b * tri.dn2;
  const double length_n = n.norm();
  const Vec3 normal = n / length_n;

  Residual r;
  r.f = h_unit + q.target_sign * normal;  // eq. 8
  const std::array<const Vec3*, 2> dp{&tri.edge1, &tri.edge2};
  const std::array<const Vec3*, 2> dn{&tri.dn1, &tri.dn2};
  for (int k = 0; k < 2; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    // omega = (X - P) / |X - P| moves with -dP.
    const Vec3 d_omega_v = unit_derivative(omega_v, length_v, -*dp[ku]);
    const Vec3 d_omega_l =
        q.light.at_infinity ? Vec3::Zero() : unit_derivative(omega_l, length_l, -*dp[ku]);
    const Vec3 d_h = unit_derivative(h_unit, length_h, q.eta * d_omega_v + d_omega_l);
    const Vec3 d_normal = unit_derivative(normal, length_n, *dn[ku]);
    r.jacobian.col(k) = d_h + q.target_sign * d_normal;
  }
  return r;
}

std::optional<IntervalResidual> evaluate_interval_residual(const RefractiveTriangle& tri,
                                                           const PathQuery& q, Interval a,
                                                           Interval b) {
  const IntervalVec3 e1(tri.edge1), e2(tri.edge2);
  const IntervalVec3 p = IntervalVec3(tri.p0) + a * e1 + b * e2;
  const IntervalVec3 minus_e1 = IntervalVec3(Vec3(-tri.edge1)), minus_e2 = IntervalVec3(Vec3(-tri.edge2));

  const IntervalVec3 to_v = IntervalVec3(q.v) - p;
  const Interval length2_v = squared_norm(to_v);
  if (!(length2_v.lo > 0.0)) return std::nullopt;
  const Interval inverse_v = reciprocal(sqrt(length2_v));
  const IntervalVec3 omega_v = inverse_v * to_v;

  IntervalVec3 omega_l(q.light.direction_to_light);
  IntervalVec3 d_omega_l_a(Vec3::Zero()), d_omega_l_b(Vec3::Zero());
  if (!q.light.at_infinity) {
    const IntervalVec3 to_l = IntervalVec3(q.light.position) - p;
    const Interval length2_l = squared_norm(to_l);
    if (!(length2_l.lo > 0.0)) return std::nullopt;
    const Interval inverse_l = reciprocal(sqrt(length2_l));
    omega_l = inverse_l * to_l;
    d_omega_l_a = interval_unit_derivative(omega_l, inverse_l, minus_e1);
    d_omega_l_b = interval_unit_derivative(omega_l, inverse_l, minus_e2);
  }
  const IntervalVec3 h = Interval(q.eta) * omega_v + omega_l;
  const Interval length2_h = squared_norm(h);
  if (!(length2_h.lo > 0.0)) return std::nullopt;
  const Interval inverse_h = reciprocal(sqrt(length2_h));
  const IntervalVec3 h_unit = inverse_h * h;

  const IntervalVec3 dn1(tri.dn1), dn2(tri.dn2);
  const IntervalVec3 n = IntervalVec3(tri.n0) + a * dn1 + b * dn2;
  const Interval length2_n = squared_norm(n);
  if (!(length2_n.lo > 0.0)) return std::nullopt;
  const Interval inverse_n = reciprocal(sqrt(length2_n));
  const IntervalVec3 normal = inverse_n * n;

  const Interval s(q.target_sign);
  IntervalResidual r;
  r.f = h_unit + s * normal;
  const auto column = [&](const IntervalVec3& minus_edge, const IntervalVec3& d_omega_l,
                          const IntervalVec3& d_n) {
    const IntervalVec3 d_omega_v = interval_unit_derivative(omega_v, inverse_v, minus_edge);
    const IntervalVec3 d_h =
        interval_unit_derivative(h_unit, inverse_h, Interval(q.eta) * d_omega_v + d_omega_l);
    return d_h + s * interval_unit_derivative(normal, inverse_n, d_n);
  };
  r.df_da = column(minus_e1, d_omega_l_a, dn1);
  r.df_db = column(minus_e2, d_omega_l_b, dn2);
  return r;
}

KrawczykVerdict krawczyk_test(const RefractiveTriangle& tri, const PathQuery& q, Interval a,
                              Interval b) {
  const auto enclosure = evaluate_interval_residual(tri, q, a, b);
  if (!enclosure) return KrawczykVerdict::undecided;
  // Eq. 12: no zero of f in the box.
  for (int k = 0; k < 3; ++k) {
    if (!enclosure->f[k].contains(0.0)) return KrawczykVerdict::no_solution;
  }
  const Vec2 m(a.mid(), b.mid());
  const Residual at_mid = evaluate_residual(tri, q, m.x(), m.y());
  Jacobian mid_jacobian;
  for (int k = 0; k < 3; ++k) {
    mid_jacobian(k, 0) = enclosure->df_da[k].mid();
    mid_jacobian(k, 1) = enclosure->df_db[k].mid();
  }
  const Eigen::Matrix2d normal_matrix = mid_jacobian.transpose() * mid_jacobian;
  if (!(std::abs(normal_matrix.determinant()) > 1e-300)) return KrawczykVerdict::undecided;
  // Pseudo-inverse M+ = (M^T M)^-1 M^T (eq. 9).
  const Eigen::Matrix<double, 2, 3> pseudo_inverse =
      normal_matrix.inverse() * mid_jacobian.transpose();
  if (!pseudo_inverse.allFinite() || !at_mid.f.allFinite()) return KrawczykVerdict::undecided;
  const Vec2 newton_point = m - pseudo_inverse * at_mid.f;
  const std::array<Interval, 2> box{a, b};
  // Eq. 11: K = m - M+ f(m) + [I - M+ F'(X)] (X - m).
  std::array<Interval, 2> k_box;
  double contraction = 0.0;  // row-sum norm of I - M+ F'(X), eq. 15
  for (int i = 0; i < 2; ++i) {
    Interval sum(newton_point[i]);
    double row = 0.0;
    for (int j = 0; j < 2; ++j) {
      const IntervalVec3& column = j == 0 ? enclosure->df_da : enclosure->df_db;
      Interval entry(i == j ? 1.0 : 0.0);
      for (int k = 0; k < 3; ++k) entry = entry - Interval(pseudo_inverse(i, k)) * column[k];
      row += entry.magnitude();
      const auto ju = static_cast<std::size_t>(j);
      sum = sum + entry * (box[ju] - Interval(m[j]));
    }
    contraction = std::max(contraction, row);
    k_box[static_cast<std::size_t>(i)] = sum;
  }
  bool inside = true;
  for (std::size_t i = 0; i < 2; ++i) {
    const Interval common = intersect(k_box[i], box[i]);
    if (common.lo > common.hi) return KrawczykVerdict::no_solution;  // eq. 13
    inside = inside && box[i].lo < k_box[i].lo && k_box[i].hi < box[i].hi;
  }
  if (inside && contraction < 1.0) return KrawczykVerdict::unique_solution;  // eqs. 14-15
  return KrawczykVerdict::undecided;
}

std::optional<Eigen::Vector2d> newton_2d(const RefractiveTriangle& tri, const PathQuery& q,
                                         Eigen::Vector2d start, double step_limit,
                                         const RefractionOptions& options,
                                         RefractionStats& stats) {
  ++stats.newton_runs;
  Vec2 x = start;
  Residual r = evaluate_residual(tri, q, x.x(), x.y());
  double norm = r.f.norm();
  for (int iteration = 0; iteration < options.max_newton_iterations; ++iteration) {
    if (!(norm > options.newton_tolerance)) return x.allFinite() ? std::optional(x) : std::nullopt;
    ++stats.newton_iterations;
    const Eigen::Matrix2d normal_matrix = r.jacobian.transpose() * r.jacobian;
    Vec2 step = -normal_matrix.ldlt().solve(r.jacobian.transpose() * r.f);  // eq. 9
    if (!step.allFinite()) return std::nullopt;
    const double step_length = step.norm();
    if (step_length > step_limit) step *= step_limit / step_length;
    // Shorten a step that does not reduce |f| (Walter §3.3).
    bool reduced = false;
    for (int halving = 0; halving < 12; ++halving) {
      const Vec2 trial = x + step;
      const Residual tr = evaluate_residual(tri, q, trial.x(), trial.y());
      const double trial_norm = tr.f.norm();
      if (trial_norm < norm) {
        x = trial;
        r = tr;
        norm = trial_norm;
        reduced = true;
        break;
      }
      step *= 0.5;
    }
    // A stall at the rounding floor is still a solution to well within Snell's 1e-10.
    if (!reduced) return norm <= 1e-11 ? std::optional(x) : std::nullopt;
    // Far outside the triangle: this start belongs to another triangle's search.
    if (std::abs(x.x()) > 4.0 || std::abs(x.y()) > 4.0) return std::nullopt;
  }
  return norm <= options.newton_tolerance ? std::optional(x) : std::nullopt;
}

std::optional<RefractionPath> accept_path(const RefractiveTriangle& tri, const PathQuery& q,
                                          double a, double b) {
  constexpr double tolerance = 1e-9;  // barycentric slack; neighbours' duplicates are merged
  if (!(a >= -tolerance && b >= -tolerance && a + b <= 1.0 + tolerance)) return std::nullopt;
  RefractionPath path;
  path.point = tri.point(a, b);
  path.shading_normal = tri.shading_normal(a, b);
  const Vec3 to_v = q.v - path.point;
  path.distance_v = to_v.norm();
  if (!(path.distance_v > 0.0)) return std::nullopt;
  path.omega_v = to_v / path.distance_v;
  if (q.light.at_infinity) {
    path.omega_l = q.light.direction_to_light;
    path.distance_l = std::numeric_limits<double>::infinity();
  } else {
    const Vec3 to_l = q.light.position - path.point;
    path.distance_l = to_l.norm();
    if (!(path.distance_l > 0.0)) return std::nullopt;
    path.omega_l = to_l / path.distance_l;
  }
  const Vec3& ng = tri.geometric_normal;
  // Sidedness (Walter §3.1, eq. 4 and §3.4): L outside, V inside, for N_s and N_g alike.
  if (!(path.omega_l.dot(path.shading_normal) > 0.0 && path.omega_v.dot(path.shading_normal) < 0.0 &&
        path.omega_l.dot(ng) > 0.0 && path.omega_v.dot(ng) < 0.0)) {
    return std::nullopt;
  }
  path.triangle = tri.index;
  path.bary_a = a;
  path.bary_b = b;
  return path;
}

std::optional<RefractionPath> find_flat_path(const RefractiveTriangle& tri, const PathQuery& q,
                                             RefractionStats& stats) {
  const Vec3& ng = tri.geometric_normal;
  if (ng.squaredNorm() == 0.0) return std::nullopt;  // degenerate triangle: no plane
  // Walter §3.2, Fig. 3: V at depth d below the plane, L at height h above it, P = V' + x e on
  // the line from V's foot V' towards L's foot, 0 <= x <= L_x.
  const double depth = (tri.p0 - q.v).dot(ng);
  if (!(depth > 0.0)) return std::nullopt;
  const Vec3 foot_v = q.v + depth * ng;
  Vec3 p = foot_v;
  if (q.light.at_infinity) {
    const double cos_l = q.light.direction_to_light.dot(ng);
    if (!(cos_l > 0.0)) return std::nullopt;
    const Vec3 tangent = q.light.direction_to_light - cos_l * ng;
    const double sin_l = tangent.norm();
    if (sin_l > 0.0) {
      // Snell sin_l = eta x / sqrt(x^2 + d^2) solved for x; none beyond the critical angle.
      const double denominator = q.eta * q.eta - sin_l * sin_l;
      if (!(denominator > 0.0)) return std::nullopt;
      p += (depth * sin_l / std::sqrt(denominator)) * (tangent / sin_l);
    }
  } else {
    const double height = (q.light.position - tri.p0).dot(ng);
    if (!(height > 0.0)) return std::nullopt;
    const Vec3 foot_l = q.light.position - height * ng;
    const double span = (foot_l - foot_v).norm();
    if (span > 0.0) {
      const Vec3 e = (foot_l - foot_v) / span;
      // g(x) = eta sin(theta_V) - sin(theta_L) increases from g(0) < 0 to g(L_x) > 0, so a
      // Newton step kept inside the bracket always converges (Walter eqs. 5-7; start eq. 6).
      const auto g = [&](double x, double& slope) {
        const double rv = std::sqrt(x * x + depth * depth);
        const double u = span - x;
        const double rl = std::sqrt(u * u + height * height);
        slope = q.eta * depth * depth / (rv * rv * rv) + height * height / (rl * rl * rl);
        return q.eta * x / rv - u / rl;
      };
      double lo = 0.0, hi = span;
      double x = span * depth / (depth + q.eta * height);
      const double scale = span + depth + height;
      for (int iteration = 0; iteration < 100; ++iteration) {
        ++stats.newton_iterations;
        double slope = 0.0;
        const double value = g(x, slope);
        if (value == 0.0) break;
        (value < 0.0 ? lo : hi) = x;
        double next = x - value / slope;
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        const double change = std::abs(next - x);
        x = next;
        if (change <= 4.0 * std::numeric_limits<double>::epsilon() * scale) break;
      }
      p += x * e;
    }
  }
  ++stats.newton_runs;
  const Vec2 ab = tri.barycentric(p);
  return accept_path(tri, q, ab.x(), ab.y());
}

void find_smooth_paths(const RefractiveTriangle& tri, const PathQuery& q,
                       const RefractionOptions& options, RefractionStats& stats,
                       std::vector<RefractionPath>& paths) {
  struct SubTriangle {
    std::array<Vec2, 3> corner;
    int depth;
  };
  // Depth-first; 3 * max depth + 1 entries bound the stack.
  std::array<SubTriangle, 64> stack;
  std::size_t size = 0;
  stack[size++] = {{Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)}, 0};
  const auto try_newton = [&](const Vec2& start, double step_limit) {
    if (const auto ab = newton_2d(tri, q, start, step_limit, options, stats)) {
      if (auto path = accept_path(tri, q, ab->x(), ab->y())) paths.push_back(*path);
    }
  };
  while (size > 0) {
    const SubTriangle sub = stack[--size];
    ++stats.subtriangles;
    std::array<Vec3, 3> normals, to_v, to_l;
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec2& c = sub.corner[k];
      const Vec3 p = tri.point(c.x(), c.y());
      normals[k] = tri.shading_normal(c.x(), c.y());
      to_v[k] = (q.v - p).normalized();
      to_l[k] = q.light.direction_from(p);
    }
    // Cone overlap (Walter §3.3.1): prune when -s H and N_s cannot meet.
    const DirectionCone normal_cone = cone_of_directions(normals);
    const DirectionCone v_cone = cone_of_directions(to_v);
    const DirectionCone l_cone = q.light.at_infinity
                                     ? DirectionCone{q.light.direction_to_light, 0.0}
                                     : cone_of_directions(to_l);
    const DirectionCone h_cone = half_vector_cone(v_cone, l_cone, q.eta);
    if (!overlap({-q.target_sign * h_cone.axis, h_cone.half_angle}, normal_cone)) continue;
    const double size_ab = std::ldexp(1.0, -sub.depth);
    const Vec2 centroid = (sub.corner[0] + sub.corner[1] + sub.corner[2]) / 3.0;
    const bool at_limit = sub.depth >= std::min(options.max_split_depth, 20);  // fits the stack
    if (options.mode == SearchMode::heuristic) {
      if (h_cone.half_angle + normal_cone.half_angle < options.cone_stop_angle || at_limit) {
        Vec2 start = centroid;
        // Walter §3.3: if |f| > 1 at the centroid, start from the best of the corners and the
        // projection of V along the mean shading normal.
        double best = evaluate_residual(tri, q, start.x(), start.y()).f.norm();
        if (!(best <= 1.0)) {
          std::array<Vec2, 4> candidates{sub.corner[0], sub.corner[1], sub.corner[2], centroid};
          const Vec3 mean_normal = (normals[0] + normals[1] + normals[2]).normalized();
          const double along = mean_normal.dot(tri.geometric_normal);
          if (std::abs(along) > 1e-12) {
            const double t = (tri.p0 - q.v).dot(tri.geometric_normal) / along;
            candidates[3] = tri.barycentric(q.v + t * mean_normal);
          }
          for (const Vec2& c : candidates) {
            if (!c.allFinite()) continue;
            const double value = evaluate_residual(tri, q, c.x(), c.y()).f.norm();
            if (value < best) {
              best = value;
              start = c;
            }
          }
        }
        try_newton(start, 0.5 * size_ab);
        continue;
      }
    } else {
      const auto [a_lo, a_hi] = std::minmax({sub.corner[0].x(), sub.corner[1].x(), sub.corner[2].x()});
      const auto [b_lo, b_hi] = std::minmax({sub.corner[0].y(), sub.corner[1].y(), sub.corner[2].y()});
      const Interval box_a(a_lo, a_hi), box_b(b_lo, b_hi);
      const KrawczykVerdict verdict = krawczyk_test(tri, q, box_a, box_b);
      if (verdict == KrawczykVerdict::no_solution) continue;
      if (verdict == KrawczykVerdict::unique_solution || at_limit) {
        if (verdict == KrawczykVerdict::undecided) ++stats.undecided_at_depth_limit;
        try_newton(Vec2(box_a.mid(), box_b.mid()), 2.0 * size_ab);
        continue;
      }
    }
    // Split at the edge midpoints into four (Walter §3.3.1).
    const Vec2 m01 = 0.5 * (sub.corner[0] + sub.corner[1]);
    const Vec2 m12 = 0.5 * (sub.corner[1] + sub.corner[2]);
    const Vec2 m20 = 0.5 * (sub.corner[2] + sub.corner[0]);
    const int depth = sub.depth + 1;
    stack[size++] = {{sub.corner[0], m01, m20}, depth};
    stack[size++] = {{m01, sub.corner[1], m12}, depth};
    stack[size++] = {{m20, m12, sub.corner[2]}, depth};
    stack[size++] = {{m01, m12, m20}, depth};
  }
}

std::optional<RefractionPath> find_straight_path(const RefractiveTriangle& tri,
                                                 const PathQuery& q) {
  const Vec3 d = q.light.at_infinity ? q.light.direction_to_light : Vec3(q.light.position - q.v);
  // Moller-Trumbore: V + t d = P(a, b).
  const Vec3 pvec = d.cross(tri.edge2);
  const double det = tri.edge1.dot(pvec);
  if (!(std::abs(det) > 0.0)) return std::nullopt;
  const Vec3 tvec = q.v - tri.p0;
  const double a = tvec.dot(pvec) / det;
  const Vec3 qvec = tvec.cross(tri.edge1);
  const double b = d.dot(qvec) / det;
  const double t = tri.edge2.dot(qvec) / det;
  if (!(t > 0.0) || (!q.light.at_infinity && !(t < 1.0))) return std::nullopt;
  return accept_path(tri, q, a, b);
}

std::optional<RefractionPath> path_with_v_on_triangle(const RefractiveTriangle& tri,
                                                      const PathQuery& q) {
  const Vec3& ng = tri.geometric_normal;
  if (ng.squaredNorm() == 0.0) return std::nullopt;
  const double scale = std::max(tri.edge1.norm(), tri.edge2.norm());
  if (!(std::abs((q.v - tri.p0).dot(ng)) <= 1e-12 * scale)) return std::nullopt;
  const Vec2 ab = tri.barycentric(q.v);
  if (!(ab.x() >= 0.0 && ab.y() >= 0.0 && ab.sum() <= 1.0)) return std::nullopt;
  RefractionPath path;
  path.point = q.v;
  path.shading_normal = tri.shading_normal(ab.x(), ab.y());
  path.omega_l = q.light.direction_from(q.v);
  path.distance_l = q.light.at_infinity ? std::numeric_limits<double>::infinity()
                                        : (q.light.position - q.v).norm();
  const double cos_l = path.omega_l.dot(path.shading_normal);
  if (!(cos_l > 0.0 && path.omega_l.dot(ng) > 0.0)) return std::nullopt;
  // The refracted travel direction into the medium (Snell about N_s); omega_V is that direction.
  const double ratio = 1.0 / q.eta;
  const double sin2_t = ratio * ratio * (1.0 - cos_l * cos_l);
  if (sin2_t >= 1.0) return std::nullopt;
  path.omega_v = -ratio * path.omega_l + (ratio * cos_l - std::sqrt(1.0 - sin2_t)) * path.shading_normal;
  path.distance_v = 0.0;
  path.triangle = tri.index;
  path.bary_a = ab.x();
  path.bary_b = ab.y();
  return path;
}

}  // namespace scatterlab
