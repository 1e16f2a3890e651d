#pragma once
// Refracted paths through one triangle (Walter et al. 2009): the 1D Newton search in the
// incidence plane for flat triangles (§3.2), and for interpolated normals the 2D Newton with the
// pseudo-inverse (§3.3, eq. 9) inside a split-and-prune over sub-triangles (§3.3.1) stopped by
// the cone-angle heuristic or decided by the Krawczyk interval test (§3.3.2).

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "scatterlab/core/triangle_mesh.hpp"
#include "scatterlab/refract/interval.hpp"
#include "scatterlab/refract/refraction_path.hpp"

namespace scatterlab {

// One boundary triangle, laid out for the solver: P(a, b) = p0 + a edge1 + b edge2 and the
// unnormalised interpolated normal n(a, b) = n0 + a dn1 + b dn2 (N_s = n / |n|).
struct RefractiveTriangle {
  Vec3 p0, edge1, edge2;
  Vec3 n0, dn1, dn2;
  Vec3 geometric_normal;  // unit, outward (zero if degenerate)
  bool smooth = false;    // false: N_s = N_g everywhere, the 1D search applies
  std::uint32_t index = 0;

  static RefractiveTriangle from_mesh(const TriangleMesh& mesh, std::size_t triangle);
  Vec3 point(double a, double b) const { return p0 + a * edge1 + b * edge2; }
  Vec3 shading_normal(double a, double b) const {
    return smooth ? Vec3((n0 + a * dn1 + b * dn2).normalized()) : geometric_normal;
  }
  // Barycentric (a, b) of a point in the triangle's plane (least squares off the plane).
  Eigen::Vector2d barycentric(const Vec3& p) const;
};

// The query a triangle is searched for, with the sign s of the target: the residual is
// f = H + s N_s with s = +1 for eta > 1 (H = -N_s, Walter eq. 4) and s = -1 for eta < 1, where
// the half-vector eta omega_V + omega_L points out of the medium.
struct PathQuery {
  Vec3 v;
  Light light;
  double eta;
  double target_sign;

  PathQuery(const Vec3& scatter_point, const Light& l, double relative_index)
      : v(scatter_point), light(l), eta(relative_index), target_sign(relative_index > 1.0 ? 1.0 : -1.0) {}
};

struct Residual {
  Vec3 f;                             // Walter eq. 8
  Eigen::Matrix<double, 3, 2> jacobian;  // columns d f / d a, d f / d b (eq. 10 chain rule)
};
Residual evaluate_residual(const RefractiveTriangle& tri, const PathQuery& q, double a, double b);

// Enclosure of f and its Jacobian over a box of (a, b); nullopt where |h| or |n| may vanish.
struct IntervalResidual {
  IntervalVec3 f, df_da, df_db;
};
std::optional<IntervalResidual> evaluate_interval_residual(const RefractiveTriangle& tri,
                                                           const PathQuery& q, Interval a,
                                                           Interval b);

enum class KrawczykVerdict { no_solution, unique_solution, undecided };
// Walter eqs. 11-15 on the box a x b.
KrawczykVerdict krawczyk_test(const RefractiveTriangle& tri, const PathQuery& q, Interval a,
                              Interval b);

// 2D Newton with the pseudo-inverse (eq. 9), steps limited to step_limit in (a, b) and shortened
// until |f| decreases. Returns (a, b) once |f| <= tolerance.
std::optional<Eigen::Vector2d> newton_2d(const RefractiveTriangle& tri, const PathQuery& q,
                                         Eigen::Vector2d start, double step_limit,
                                         const RefractionOptions& options, RefractionStats& stats);

// A path at barycentric (a, b) if it lies in the triangle and meets the sidedness conditions
// (Walter §3.1: omega_L on the outer and omega_V on the inner side of both N_s and N_g).
std::optional<RefractionPath> accept_path(const RefractiveTriangle& tri, const PathQuery& q,
                                          double a, double b);

// The 1D search for a flat triangle (§3.2); at most one path.
std::optional<RefractionPath> find_flat_path(const RefractiveTriangle& tri, const PathQuery& q,
                                             RefractionStats& stats);

// Every path through a triangle with interpolated normals (§3.3), appended to `paths`.
void find_smooth_paths(const RefractiveTriangle& tri, const PathQuery& q,
                       const RefractionOptions& options, RefractionStats& stats,
                       std::vector<RefractionPath>& paths);

// eta = 1: the straight segment (or ray) from V towards the light, where it leaves through tri.
std::optional<RefractionPath> find_straight_path(const RefractiveTriangle& tri,
                                                 const PathQuery& q);

// V lying on the triangle (within 1e-12 of the triangle's size): P = V.
std::optional<RefractionPath> path_with_v_on_triangle(const RefractiveTriangle& tri,
                                                      const PathQuery& q);

}  // namespace scatterlab
