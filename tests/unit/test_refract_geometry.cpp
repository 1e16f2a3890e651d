// Fresnel, the procedural meshes, and the flat-boundary physics of the refractive solver
// (Walter et al. 2009): Snell to 1e-10, D from ray differentials against eq. 18 and against a
// finite-difference trace, and energy balance of the path irradiance.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/core/quadrature.hpp"
#include "scatterlab/refract/path_contribution.hpp"
#include "scatterlab/refract/refractive_solver.hpp"

namespace scatterlab {
namespace {

double snell_residual(const RefractionPath& p, double eta) {
  // Tangential parts of omega_L and eta omega_V cancel about N_s (Walter §3.1).
  return (p.omega_l + eta * p.omega_v).cross(p.shading_normal).norm();
}

TEST(Fresnel, NormalIncidenceUnitIndexAndTotalInternalReflection) {
  for (const double eta : {1.33, 1.5, 0.7}) {
    EXPECT_NEAR(fresnel_dielectric_reflectance(1.0, eta), std::pow((eta - 1) / (eta + 1), 2),
                1e-15);
  }
  EXPECT_EQ(fresnel_dielectric_reflectance(0.3, 1.0), 0.0);
  const double critical = std::asin(1.0 / 1.5);
  EXPECT_EQ(fresnel_dielectric_reflectance(std::cos(critical + 1e-6), 1.0 / 1.5), 1.0);
  EXPECT_LT(fresnel_dielectric_reflectance(std::cos(critical - 1e-3), 1.0 / 1.5), 1.0);
  EXPECT_NEAR(fresnel_dielectric_reflectance(0.0, 1.5), 1.0, 1e-15);
  // Reciprocity: T is the same for the two directions of one refracted ray.
  for (const double theta_i : {0.1, 0.5, 1.0, 1.4}) {
    const double sin_t = std::sin(theta_i) / 1.5;
    EXPECT_NEAR(fresnel_dielectric_transmittance(std::cos(theta_i), 1.5),
                fresnel_dielectric_transmittance(std::sqrt(1 - sin_t * sin_t), 1.0 / 1.5), 1e-14);
  }
}

double signed_volume(const TriangleMesh& mesh) {
  double volume = 0.0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    volume += mesh.vertex(t, 0).dot(mesh.vertex(t, 1).cross(mesh.vertex(t, 2))) / 6.0;
  }
  return volume;
}

TEST(ProceduralMeshes, ClosedOutwardAndOfTheRequestedSize) {
  const TriangleMesh sphere = make_sphere(1.0, 40, 80, true);
  sphere.validate();
  EXPECT_NEAR(signed_volume(sphere), 4.0 / 3.0 * pi, 0.02);  // inscribed polyhedron
  for (std::size_t t = 0; t < sphere.triangle_count(); ++t) {
    EXPECT_GT(sphere.geometric_normal(t).dot(sphere.vertex(t, 0) + sphere.vertex(t, 1)), 0.0);
  }
  const TriangleMesh bumpy = make_bumpy_sphere(1.0, 0.05, 6, 71, 72);
  bumpy.validate();
  EXPECT_EQ(bumpy.triangle_count(), 10080u);
  EXPECT_GT(signed_volume(bumpy), 0.0);
  const TriangleMesh tile = make_rounded_tile(1.0, 1.0, 0.25, 0.3, 24, 48);
  tile.validate();
  EXPECT_NEAR(signed_volume(tile), 8.0 * 0.25, 0.4);  // a rounded box, a little under 2
  TriangleMesh bad = sphere;
  bad.triangles[3][1] = 1u << 30;
  EXPECT_THROW(bad.validate(), InputError);
}

// Two parts in one mesh: the volumes add, the second part's vertices are moved and renumbered,
// and shading normals are kept only for two meshes that both have them.
TEST(ProceduralMeshes, AppendedPartsMakeOneMesh) {
  TriangleMesh two = make_rounded_tile(1.0, 1.0, 0.25, 0.3, 12, 24);
  const double one = signed_volume(two);
  const std::size_t positions = two.positions.size();
  append_mesh(two, make_rounded_tile(1.0, 1.0, 0.25, 0.3, 12, 24), Vec3(0.0, 0.0, 5.0));
  two.validate();
  EXPECT_EQ(two.positions.size(), 2 * positions);
  EXPECT_EQ(two.normals.size(), 2 * positions);
  EXPECT_NEAR(signed_volume(two), 2.0 * one, 1e-12);
  EXPECT_EQ(two.vertex(two.triangle_count() - 1, 0).z(),
            two.vertex(two.triangle_count() / 2 - 1, 0).z() + 5.0);
  EXPECT_THROW(append_mesh(two, make_flat_square(1.0, 1), Vec3::Zero()), std::invalid_argument);
}

// Exact plane path for the test: Snell solved by bisection on the incidence-plane equation.
Vec3 plane_path(const Vec3& v, const Vec3& l, double eta) {
  const double depth = -v.z(), height = l.z();
  const Vec3 foot_v(v.x(), v.y(), 0.0), foot_l(l.x(), l.y(), 0.0);
  const double span = (foot_l - foot_v).norm();
  double lo = 0.0, hi = span;
  for (int i = 0; i < 200; ++i) {
    const double x = 0.5 * (lo + hi);
    const double g = eta * x / std::hypot(x, depth) - (span - x) / std::hypot(span - x, height);
    (g < 0 ? lo : hi) = x;
  }
  return foot_v + 0.5 * (lo + hi) * (foot_l - foot_v) / span;
}

TEST(RefractiveSolverFlat, PlanePathMatchesSnellAndEquation18) {
  const TriangleMesh plane = make_flat_square(50.0, +1);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const double eta : {1.5, 1.33, 0.75, 2.4}) {
    const RefractiveSolver solver(plane, eta);
    for (int trial = 0; trial < 50; ++trial) {
      const Vec3 v(2 * u(rng), 2 * u(rng), -0.05 - 2 * (1 + u(rng)));
      const Vec3 l(3 * u(rng), 3 * u(rng), 0.05 + 2 * (1 + u(rng)));
      const auto paths = solver.find_paths(v, Light::point(l));
      ASSERT_EQ(paths.size(), 1u);
      const RefractionPath& p = paths[0];
      EXPECT_LE(snell_residual(p, eta), 1e-10);
      EXPECT_LE((p.point - plane_path(v, l, eta)).norm(), 1e-9);
      const double d_general = refraction_distance_factor(solver.triangle(p.triangle), p, eta, false);
      EXPECT_NEAR(d_general / flat_refraction_distance_factor(p, eta, false), 1.0, 1e-10);
    }
  }
}

TEST(RefractiveSolverFlat, NormalIncidenceDistanceFactorAndUnitIndex) {
  const TriangleMesh plane = make_flat_square(10.0, +1);
  const RefractiveSolver solver(plane, 1.5);
  const auto paths = solver.find_paths(Vec3(0.2, 0.1, -1.0), Light::point(Vec3(0.2, 0.1, 2.0)));
  ASSERT_EQ(paths.size(), 1u);
  const double d = refraction_distance_factor(solver.triangle(paths[0].triangle), paths[0], 1.5, false);
  EXPECT_NEAR(d, std::pow(1.0 + 1.5 * 2.0, 2), 1e-12);  // Walter §4: (|P-V| + eta |L-P|)^2
  // eta = 1: the straight segment, D = |L - V|^2.
  const RefractiveSolver unit(plane, 1.0);
  const Vec3 v(0.3, -0.2, -1.0), l(1.3, 0.6, 2.0);
  const auto straight = unit.find_paths(v, Light::point(l));
  ASSERT_EQ(straight.size(), 1u);
  EXPECT_LE((straight[0].point - (v + (l - v) / 3.0)).norm(), 1e-14);
  EXPECT_NEAR(refraction_distance_factor(unit.triangle(straight[0].triangle), straight[0], 1.0, false),
              (l - v).squaredNorm(), 1e-12);
}

// Trace the perturbed ray from V, refract about the interpolated normal where it meets the
// triangle's plane, and intersect the plane through L normal to omega_L.
Vec3 trace_to_light_plane(const RefractiveTriangle& tri, const Vec3& v, const Vec3& d, double eta,
                          const Vec3& l, const Vec3& omega_l) {
  const Vec3& ng = tri.geometric_normal;
  const double t = (tri.p0 - v).dot(ng) / d.dot(ng);
  const Vec3 p = v + t * d;
  const Eigen::Vector2d ab = tri.barycentric(p);
  const Vec3 n = tri.shading_normal(ab.x(), ab.y());
  const double cos_i = d.dot(n);
  const double cos_o = std::sqrt(1.0 - eta * eta * (1.0 - cos_i * cos_i));
  const Vec3 out = eta * d + (cos_o - eta * cos_i) * n;
  const double s = (l - p).dot(omega_l) / out.dot(omega_l);
  return p + s * out;
}

TEST(RefractiveSolverFlat, DistanceFactorMatchesFiniteDifferences) {
  // A single smooth triangle with strongly varying normals, so N_s' matters.
  TriangleMesh mesh;
  mesh.positions = {Vec3(-2, -2, 0), Vec3(2, -2, 0.3), Vec3(0, 2, -0.2)};
  mesh.normals = {Vec3(-0.3, -0.2, 1).normalized(), Vec3(0.25, -0.1, 1).normalized(),
                  Vec3(0.05, 0.35, 1).normalized()};
  mesh.triangles = {{0u, 1u, 2u}};
  for (const double eta : {1.5, 0.8}) {
    RefractionOptions options;
    options.mode = SearchMode::guaranteed;
    const RefractiveSolver solver(mesh, eta, options);
    const Vec3 v(0.1, -0.3, -1.2), l(0.8, 0.4, 2.5);
    const auto paths = solver.find_paths(v, Light::point(l));
    ASSERT_GE(paths.size(), 1u);
    for (const RefractionPath& p : paths) {
      const RefractiveTriangle& tri = solver.triangle(p.triangle);
      const double d = refraction_distance_factor(tri, p, eta, false);
      const Vec3 dir = -p.omega_v;
      const Frame frame(dir);
      const double h = 1e-6;
      std::array<Vec3, 2> derivative;
      for (int k = 0; k < 2; ++k) {
        const Vec3& e = k == 0 ? frame.tangent : frame.bitangent;
        const Vec3 plus = trace_to_light_plane(tri, v, (dir + h * e).normalized(), eta, l, p.omega_l);
        const Vec3 minus = trace_to_light_plane(tri, v, (dir - h * e).normalized(), eta, l, p.omega_l);
        derivative[static_cast<std::size_t>(k)] = (plus - minus) / (2 * h);
      }
      EXPECT_NEAR(d / derivative[0].cross(derivative[1]).norm(), 1.0, 1e-6) << "eta " << eta;
    }
  }
}

TEST(RefractiveSolverFlat, PathIrradianceConservesTransmittedPower) {
  // Point light of unit intensity at height h above a clear (sigma_t -> 0) flat medium: the
  // power crossing the plane at depth z, int E cos(theta_V) dA, equals int I T dOmega over the
  // lower hemisphere. Checks the eta^2 / D normalisation independently of eq. 18.
  for (const double eta : {1.5, 0.7}) {
    const TriangleMesh plane = make_flat_square(1e4, +1);
    const RefractiveSolver solver(plane, eta);
    const double height = 0.7, depth = 1.3;
    const auto power_per_radius = [&](double rho) {
      if (rho == 0.0) return 0.0;
      const auto paths = solver.find_paths(Vec3(rho, 0, -depth), Light::point(Vec3(0, 0, height)));
      if (paths.empty()) return 0.0;
      const PathContribution c =
          path_contribution(solver.triangle(paths[0].triangle), paths[0], eta, 0.0, false);
      return 2 * pi * rho * c.irradiance * depth / paths[0].distance_v;
    };
    const std::vector<double> breaks{0.0, 1.0, 3.0, 10.0, 100.0, 2000.0};
    const QuadratureResult crossing =
        integrate_adaptive(power_per_radius, breaks, QuadratureOptions{0.0, 1e-9, 2000});
    const QuadratureResult transmitted = integrate_adaptive(
        [&](double theta) {
          return 2 * pi * std::sin(theta) * fresnel_dielectric_transmittance(std::cos(theta), eta);
        },
        0.0, 0.5 * pi);
    // The far tail beyond rho = 2000 carries the grazing light: about 1e-3 of T for eta < 1 is
    // cut at the critical angle already; for eta > 1 the tail is O(h / 2000).
    EXPECT_NEAR(crossing.value / transmitted.value, 1.0, 2e-3) << "eta " << eta;
  }
}

TEST(RefractiveSolverFlat, DirectionalLightTotalInternalReflectionAndGrazing) {
  const TriangleMesh plane = make_flat_square(100.0, +1);
  const RefractiveSolver solver(plane, 1.5);
  const Vec3 v(0.0, 0.0, -1.0);
  const Vec3 towards = Vec3(std::sin(0.6), 0.0, std::cos(0.6));
  const auto paths = solver.find_paths(v, Light::directional(towards));
  ASSERT_EQ(paths.size(), 1u);
  EXPECT_LE(snell_residual(paths[0], 1.5), 1e-12);
  const RefractiveTriangle& tri = solver.triangle(paths[0].triangle);
  EXPECT_NEAR(refraction_distance_factor(tri, paths[0], 1.5, true) /
                  flat_refraction_distance_factor(paths[0], 1.5, true),
              1.0, 1e-12);
  // Parallel light at normal incidence stays parallel: E = E_0 T.
  const auto normal = solver.find_paths(v, Light::directional(Vec3::UnitZ()));
  ASSERT_EQ(normal.size(), 1u);
  EXPECT_NEAR(path_contribution(tri, normal[0], 1.5, 0.0, true).irradiance,
              fresnel_dielectric_transmittance(1.0, 1.5), 1e-14);
  // eta < 1: a directional light beyond asin(eta) from the normal is totally reflected.
  const RefractiveSolver rare(plane, 0.75);
  const double critical = std::asin(0.75);
  EXPECT_EQ(rare.find_paths(v, Light::directional(Vec3(std::sin(critical + 1e-3), 0,
                                                        std::cos(critical + 1e-3))))
                .size(),
            0u);
  EXPECT_EQ(rare.find_paths(v, Light::directional(Vec3(std::sin(critical - 1e-3), 0,
                                                        std::cos(critical - 1e-3))))
                .size(),
            1u);
  // Grazing point light: L nearly in the plane, far away; the path exists and obeys Snell.
  const auto grazing = solver.find_paths(v, Light::point(Vec3(60.0, 0.0, 1e-6)));
  ASSERT_EQ(grazing.size(), 1u);
  EXPECT_LE(snell_residual(grazing[0], 1.5), 1e-10);
  EXPECT_GT(grazing[0].omega_v.dot(Vec3(-1, 0, 0)), 0.0);
  // A light below the plane, or V above it: no path.
  EXPECT_EQ(solver.find_paths(v, Light::point(Vec3(1, 0, -0.5))).size(), 0u);
  EXPECT_EQ(solver.find_paths(Vec3(0, 0, 0.5), Light::point(Vec3(1, 0, 2))).size(), 0u);
}

TEST(RefractiveSolverFlat, VOnTheBoundaryAndDegenerateTriangles) {
  const TriangleMesh plane = make_flat_square(10.0, +1);
  const RefractiveSolver solver(plane, 1.5);
  const Vec3 v(0.3, 0.4, 0.0);
  const Vec3 l(1.3, 0.4, 1.0);
  const auto paths = solver.find_paths(v, Light::point(l));
  ASSERT_EQ(paths.size(), 1u);
  EXPECT_EQ(paths[0].point, v);
  EXPECT_LE(snell_residual(paths[0], 1.5), 1e-14);
  const PathContribution c =
      path_contribution(solver.triangle(paths[0].triangle), paths[0], 1.5, 1.0, false);
  // E normal to the refracted ray times cos(theta_V) is the surface irradiance I cos(theta_L) T / d^2.
  const double cos_l = paths[0].omega_l.z(), cos_v = -paths[0].omega_v.z();
  EXPECT_NEAR(c.irradiance * cos_v,
              fresnel_dielectric_transmittance(cos_l, 1.5) * cos_l / (l - v).squaredNorm(), 1e-12);

  // A zero-area triangle and a 1e-9-thin sliver next to a good one: no crash, no NaN, and the
  // good triangle still gives its path.
  TriangleMesh mesh;
  mesh.positions = {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1, 0), Vec3(3, 3, 0),
                    Vec3(5, 3, 0), Vec3(4, 3 + 1e-9, 0)};
  mesh.triangles = {{0u, 1u, 2u}, {0u, 0u, 1u}, {3u, 4u, 5u}, {1u, 1u, 1u}};
  for (const double eta : {1.5, 0.7, 1.0}) {
    const RefractiveSolver s(mesh, eta);
    const auto found = s.find_paths(Vec3(0, 0, -1), Light::point(Vec3(0.2, 0.1, 1)));
    ASSERT_EQ(found.size(), 1u) << eta;
    EXPECT_EQ(found[0].triangle, 0u);
    EXPECT_TRUE(found[0].point.allFinite());
    // Through the sliver: the point exactly below its long edge's middle.
    const auto sliver = s.find_paths(Vec3(4, 3 + 2e-10, -1), Light::point(Vec3(4, 3 + 2e-10, 1)));
    for (const RefractionPath& p : sliver) EXPECT_TRUE(p.point.allFinite());
  }
}

}  // namespace
}  // namespace scatterlab
