// The directional light on a convex mesh (mesh/mesh_light.hpp) starts its photons on a facet
// drawn in proportion to its shadow and uniformly over it: held against lines drawn uniformly
// over a disc across the light and traced with Embree, facet by facet (4 sigma each, fixed
// seeds), and in the mean point of entry.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "mesh/mesh_light.hpp"
#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/core/random.hpp"
#include "scatterlab/mesh/mesh_ray_tracer.hpp"

namespace scatterlab {
namespace {

// The facet whose plane and triangle hold `point`.
std::size_t facet_holding(const TriangleMesh& mesh, const Vec3& point) {
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Vec3 &a = mesh.vertex(t, 0), &b = mesh.vertex(t, 1), &c = mesh.vertex(t, 2);
    const Vec3 normal = (b - a).cross(c - a);
    if (std::abs(normal.normalized().dot(point - a)) > 1e-12) continue;
    const double area = normal.squaredNorm();
    const double beta = (point - a).cross(c - a).dot(normal) / area;
    const double gamma = (b - a).cross(point - a).dot(normal) / area;
    if (beta >= -1e-12 && gamma >= -1e-12 && beta + gamma <= 1.0 + 1e-12) return t;
  }
  return mesh.triangle_count();
}

TEST(MeshLight, DirectionalLightOnAConvexMeshStartsOnFacetsAsItsLinesMeetThem) {
  const TriangleMesh mesh = make_sphere(1.0, 5, 8, false);  // 64 facets
  const MeshRayTracer tracer(mesh);
  const MeshBoundary<false> boundary(tracer, mesh, 1.0);
  ASSERT_TRUE(boundary.convex());
  const Vec3 direction = Vec3(0.3, -0.4, 1.0).normalized();
  const MeshLight<false> light(boundary, MeshLight<false>::Kind::directional, Vec3::Zero(),
                               direction, Vec3::Zero(), 1.0);
  const int photons = 400'000;
  const std::size_t n = mesh.triangle_count();

  std::vector<double> launched(n + 1, 0.0), traced(n + 1, 0.0);
  Vec3 launched_mean = Vec3::Zero(), traced_mean = Vec3::Zero();
  for (int k = 0; k < photons; ++k) {
    PhotonRandom random(7, static_cast<std::uint64_t>(k));
    Vec3 start, heading;
    ASSERT_TRUE(light.launch(random, start, heading));  // index matched: every photon enters
    EXPECT_LT((heading - direction).norm(), 1e-15);
    launched[facet_holding(mesh, start)] += 1.0;
    launched_mean += start / photons;
  }
  // Lines uniform over the disc of radius 1.1 across the light, as many as meet the sphere.
  const Frame across(direction);
  std::mt19937_64 generator(3);
  std::uniform_real_distribution<double> uniform(-1.1, 1.1);
  for (int met = 0; met < photons;) {
    const double x = uniform(generator), y = uniform(generator);
    if (x * x + y * y > 1.21) continue;
    MeshHit hit;
    if (!tracer.intersect(across.to_world(x, y, 0.0) - 3.0 * direction, direction, 0.0, 10.0,
                          hit)) {
      continue;
    }
    ++met;
    traced[hit.triangle] += 1.0;
    traced_mean +=
        (across.to_world(x, y, 0.0) - 3.0 * direction + hit.distance * direction) / photons;
  }
  EXPECT_EQ(launched[n], 0.0) << "starts on no facet";
  int facing = 0;
  for (std::size_t t = 0; t < n; ++t) {
    const double p1 = launched[t] / photons, p2 = traced[t] / photons;
    const double sigma = std::sqrt(std::max(p1 * (1.0 - p1) + p2 * (1.0 - p2), 1e-12) / photons);
    EXPECT_NEAR(p1, p2, 4.0 * sigma) << "facet " << t;
    facing += p1 > 0.0;
    if (mesh.geometric_normal(t).dot(direction) >= 0.0) {
      EXPECT_EQ(launched[t], 0.0) << "facet " << t << " faces away from the light";
    }
  }
  EXPECT_GE(facing, 24);
  // The mean point of entry: each coordinate within 4 sigma (of both means; |x| <= 1).
  EXPECT_LT((launched_mean - traced_mean).norm(), 4.0 * std::sqrt(2.0 / photons));
}

}  // namespace
}  // namespace scatterlab
