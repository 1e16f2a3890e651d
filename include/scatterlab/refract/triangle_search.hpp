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

// d f / d V . direction at (a, b): how the residual moves when the scattering point V moves
// (Holzschuch 2013, §3.2.3: the x column of the 3 x 3 Jacobian, by the rule of eq. 8; omega_L and
// N_s do not depend on V).
Vec3 residual_derivative_along_v(const RefractiveTriangle& tri, const PathQuery& q, double a,
                                 double b, const Vec3& direction);

// Gauss-Newton with the pseudo-inverse (Walter eq. 9) for any residual R^2 -> R^3 whose two
// parameters are of unit scale: `residual(x)` returns a Residual (f and the 3 x 2 Jacobian).
// Steps are limited to step_limit and shortened until |f| decreases (Walter §3.3); the search
// gives up once it wanders beyond |x_i| > 4. Returns x once |f| <= options.newton_tolerance.
template <class ResidualAt>
std::optional<Eigen::Vector2d> gauss_newton_2d(ResidualAt&& residual, Eigen::Vector2d start,
                                               double step_limit, const RefractionOptions& options,
                                               RefractionStats& stats) {
  ++stats.newton_runs;
  Eigen::Vector2d x = start;
  Residual r = residual(x);
  double norm = r.f.norm();
  for (int iteration = 0; iteration < options.max_newton_iterations; ++iteration) {
    if (!(norm > options.newton_tolerance)) return x.allFinite() ? std::optional(x) : std::nullopt;
    ++stats.newton_iterations;
    const Eigen::Matrix2d normal_matrix = r.jacobian.transpose() * r.jacobian;
    Eigen::Vector2d step = -normal_matrix.ldlt().solve(r.jacobian.transpose() * r.f);  // eq. 9
    if (!step.allFinite()) return std::nullopt;
    const double step_length = step.norm();
    if (step_length > step_limit) step *= step_limit / step_length;
    bool reduced = false;
    for (int halving = 0; halving < 12; ++halving) {
      const Eigen::Vector2d trial = x + step;
      const Residual tr = residual(trial);
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
    // Far outside the unit domain: this start belongs to another search.
    if (std::abs(x.x()) > 4.0 || std::abs(x.y()) > 4.0) return std::nullopt;
  }
  return norm <= options.newton_tolerance ? std::optional(x) : std::nullopt;
}

// 2D Newton with the pseudo-inverse (eq. 9) on the triangle's (a, b), steps limited to
// step_limit in (a, b) and shortened until |f| decreases. Returns (a, b) once |f| <= tolerance.
std::optional<Eigen::Vector2d> newton_2d(const RefractiveTriangle& tri, const PathQuery& q,
                                         Eigen::Vector2d start, double step_limit,
                                         const RefractionOptions& options, RefractionStats& stats);

// Slack on the barycentric coordinates with which accept_path admits a point to the triangle.
inline constexpr double barycentric_tolerance = 1e-9;

// A path at barycentric (a, b) if it lies in the triangle and meets the sidedness conditions
// (Walter §3.1: omega_L on the outer and omega_V on the inner side of both N_s and N_g).
std::optional<RefractionPath> accept_path(const RefractiveTriangle& tri, const PathQuery& q,
                                          double a, double b);

// The refraction point of the flat search (§3.2) in the triangle's plane, whether or not it lies
// in the triangle: nullopt if V is not below the plane, a point light not above it, or a
// directional light beyond the critical angle.
std::optional<Vec3> flat_refraction_point(const RefractiveTriangle& tri, const PathQuery& q,
                                          RefractionStats& stats);

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
