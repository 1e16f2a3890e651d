// The clearance grid (mesh/surface_clearance.hpp) is a lower bound: from points inside a
// shape that is not convex, no ray meets the surface within the clearance, and points outside
// it read 0; and it is of use: deep inside it is the Chebyshev bound it promises. In a convex
// shape, a segment from a point inside to a point of a cell with a clearance never meets the
// surface, which is how the lane walk passes such flights (transport/object_boundary.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mesh/surface_clearance.hpp"
#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/mesh/mesh_ray_tracer.hpp"

namespace scatterlab {
namespace {

TEST(SurfaceClearance, NoRayMeetsTheSurfaceWithinIt) {
  const TriangleMesh mesh = make_bumpy_sphere(5.0, 0.2, 4, 41, 48);
  const MeshRayTracer tracer(mesh);
  const SurfaceClearance clearance(mesh, tracer, 48);
  std::mt19937_64 generator(3);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  int checked = 0, positive = 0, outside = 0;
  while (checked < 2000) {
    const Vec3 p = 5.0 * Vec3(uniform(generator), uniform(generator), uniform(generator));
    if (tracer.count_crossings(p, Vec3(0.5773, 0.6123, 0.5407).normalized()) % 2 == 0) {
      // Outside, within the grid's box: 0, so that the lane walk never takes a flight that ends
      // there for one that stays inside (transport/object_boundary.hpp).
      ASSERT_EQ(clearance.at(p), 0.0) << "outside at " << p.transpose();
      ++outside;
      continue;
    }
    ++checked;
    const double reach = clearance.at(p);
    if (reach > 0.0) ++positive;
    for (int k = 0; k < 64; ++k) {
      const Vec3 way =
          Vec3(uniform(generator), uniform(generator), uniform(generator)).normalized();
      MeshHit hit;
      ASSERT_FALSE(tracer.intersect(p, way, 0.0, reach, hit))
          << "a surface point at " << hit.distance << " within the clearance " << reach;
    }
  }
  // Most of the shape is more than two cells (of about 10 / 48) from its surface.
  EXPECT_GT(positive, 1000);
  // From the centre the surface is at 5 (1 - 0.2) = 4 or more: at least 4 / sqrt(3) cells of
  // Chebyshev distance away, less the bound's cell and the cell the centre is in.
  const double cell = mesh.bounds().diagonal() / std::sqrt(3.0) / 48.0 * 1.05;
  EXPECT_GT(clearance.at(Vec3::Zero()), 4.0 / std::sqrt(3.0) - 2.5 * cell);
  EXPECT_EQ(clearance.at(Vec3(100.0, 0.0, 0.0)), 0.0);
  EXPECT_GT(outside, 500);  // the corners of the box about the shape
}

TEST(SurfaceClearance, CellsWithAClearanceAreInsideAConvexShape) {
  const TriangleMesh mesh = make_sphere(5.0, 24, 48, false);
  const MeshRayTracer tracer(mesh);
  const SurfaceClearance clearance(mesh, tracer, 48);
  const Vec3 probe = Vec3(0.5773, 0.6123, 0.5407).normalized();
  std::mt19937_64 generator(5);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  int segments = 0, near_surface = 0;
  for (int draw = 0; draw < 100000; ++draw) {
    const Vec3 p = 5.0 * Vec3(uniform(generator), uniform(generator), uniform(generator));
    const Vec3 q = 5.0 * Vec3(uniform(generator), uniform(generator), uniform(generator));
    if (tracer.count_crossings(p, probe) % 2 == 0 || !(clearance.at(q) > 0.0)) continue;
    ++segments;
    near_surface += q.norm() > 4.5;
    MeshHit hit;
    ASSERT_FALSE(tracer.intersect(p, (q - p).normalized(), 0.0, (q - p).norm(), hit))
        << "from " << p.transpose() << " to " << q.transpose() << ", clearance "
        << clearance.at(q);
  }
  // About a quarter of the pairs; cells wholly inside reach within a cell or two (about 0.2) of
  // the surface at 4.95 or more.
  EXPECT_GT(segments, 15000);
  EXPECT_GT(near_surface, 1000);
}

}  // namespace
}  // namespace scatterlab
