// The walks over a convex mesh's facets (mesh/convex_crossing.hpp) find the facet and the
// distance at which Embree sees a ray from inside leave, from points inside and from points on
// the surface after a reflection, and a ray from outside enter or miss, on shapes with slivers
// at a pole (the UV sphere), coplanar facets (a box), rounded edges (a tile) and a long bar
// (where the walks start far from where they end); and the core the lanes pass flights into
// lies inside and touches the surface.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "mesh/convex_crossing.hpp"
#include "mesh/convex_mesh.hpp"
#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/mesh/mesh_ray_tracer.hpp"

namespace scatterlab {
namespace {

Vec3 random_direction(std::mt19937_64& generator) {
  std::normal_distribution<double> normal;
  return Vec3(normal(generator), normal(generator), normal(generator)).normalized();
}

// Embree's first crossing from `origin` along `direction` beyond `t_near`, facing out (`out`) or
// in.
bool embree_crossing(const MeshRayTracer& tracer, const TriangleMesh& mesh, const Vec3& origin,
                     const Vec3& direction, double t_near, bool out, MeshHit& hit) {
  const double far = std::numeric_limits<double>::infinity();
  while (tracer.intersect(origin, direction, t_near, far, hit)) {
    if ((mesh.geometric_normal(hit.triangle).dot(direction) > 0.0) == out) return true;
    t_near = hit.distance + tracer.epsilon();
  }
  return false;
}

// Walks `rays` rays from points drawn inside by `inside`, then one reflection each from where
// it left, against Embree: the same distance, and the same facet
// or, where the ray leaves through an edge or a corner, a facet through the same point.
template <typename Inside>
void leaves_where_embree_does(const TriangleMesh& mesh, Inside inside, int rays) {
  ASSERT_TRUE(bounds_convex_solid(mesh));
  const MeshRayTracer tracer(mesh);
  const ConvexCrossing walk(mesh, tracer);
  const double size = mesh.bounds().diagonal();
  std::mt19937_64 generator(11);
  int other_facet = 0, at_edge = 0;
  for (int ray = 0; ray < rays; ++ray) {
    Vec3 origin = inside(generator);
    Vec3 direction = random_direction(generator);
    for (int leg = 0; leg < 2; ++leg) {
      MeshCrossing leaving;
      double cos_incidence = 0.0;
      ASSERT_EQ(walk.leave(origin, direction, leaving, cos_incidence),
                ConvexCrossing::Walk::crosses)
          << "ray " << ray << " leg " << leg;
      if (leg == 1 && leaving.distance < tracer.epsilon()) {
        // Reflected near an edge, out through the facet across it: closer than Embree looks.
        EXPECT_NEAR(leaving.normal.dot(origin - mesh.vertex(leaving.triangle, 0)), 0.0,
                    tracer.epsilon());
        ++at_edge;
        break;
      }
      MeshHit hit;
      ASSERT_TRUE(embree_crossing(tracer, mesh, origin, direction,
                                  leg == 0 ? 0.0 : tracer.epsilon(), true, hit))
          << "ray " << ray << " leg " << leg << ", walked " << leaving.distance;
      // Embree's distance is good to single precision across the facet's plane: 1/cos along
      // the ray.
      ASSERT_NEAR(leaving.distance, hit.distance, 1e-6 * size / cos_incidence)
          << "ray " << ray << " leg " << leg << ", facets " << leaving.triangle << " and "
          << hit.triangle;
      EXPECT_NEAR(cos_incidence, leaving.normal.dot(direction), 1e-15);
      EXPECT_GT(cos_incidence, 0.0);
      if (leaving.triangle != hit.triangle) ++other_facet;
      // Reflected back in from the point it left at.
      origin += leaving.distance * direction;
      direction -= 2.0 * cos_incidence * leaving.normal;
    }
  }
  // Rays through an edge are rare: a facet other than Embree's one for very few.
  EXPECT_LE(other_facet, rays / 1000 + 1);
  EXPECT_LE(at_edge, rays / 1000 + 1);
}

// Lines from outside, from a sphere about the object towards points of a ball a little larger
// than it, some away from it: the walk enters where Embree does, and misses when it does.
void enters_where_embree_does(const TriangleMesh& mesh, int rays, int least_hits) {
  const MeshRayTracer tracer(mesh);
  const ConvexCrossing walk(mesh, tracer);
  const BoundingBox box = mesh.bounds();
  const double reach = 0.5 * box.diagonal();
  std::mt19937_64 generator(13);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  int hits = 0, misses = 0, gave_up = 0;
  for (int ray = 0; ray < rays; ++ray) {
    const Vec3 origin = box.center() + 1.5 * reach * random_direction(generator);
    const Vec3 target =
        box.center() + 1.1 * reach * std::cbrt(uniform(generator)) * random_direction(generator);
    const Vec3 direction = (ray % 10 == 0 ? origin - target : target - origin).normalized();
    MeshCrossing entering;
    double cos_incidence = 0.0;
    const ConvexCrossing::Walk walked = walk.enter(origin, direction, entering, cos_incidence);
    MeshHit hit;
    const bool meets = embree_crossing(tracer, mesh, origin, direction, 0.0, false, hit);
    if (walked == ConvexCrossing::Walk::gave_up) {
      ++gave_up;
      continue;
    }
    ASSERT_EQ(walked == ConvexCrossing::Walk::crosses, meets) << "ray " << ray;
    if (!meets) {
      ++misses;
      continue;
    }
    ++hits;
    ASSERT_NEAR(entering.distance, hit.distance, 1e-6 * reach / cos_incidence)
        << "ray " << ray << ", facets " << entering.triangle << " and " << hit.triangle;
    EXPECT_NEAR(cos_incidence, -entering.normal.dot(direction), 1e-15);
  }
  EXPECT_GE(hits, least_hits);
  EXPECT_GT(misses, rays / 10);
  EXPECT_EQ(gave_up, 0);
}

// Points uniform in the ball of radius `r` about the origin.
auto in_ball(double r) {
  return [r](std::mt19937_64& generator) {
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    for (;;) {
      const Vec3 p(uniform(generator), uniform(generator), uniform(generator));
      if (p.squaredNorm() < 1.0) return Vec3(r * p);
    }
  };
}

TEST(ConvexCrossing, LeavesAUvSphereWhereEmbreeSays) {
  // 9 216 facets, 96 slivers about each pole.
  leaves_where_embree_does(make_sphere(10.0, 49, 96, false), in_ball(9.9), 20000);
}

TEST(ConvexCrossing, LeavesABoxOfCoplanarFacetsWhereEmbreeSays) {
  const Vec3 half(1.0, 2.0, 0.5);
  leaves_where_embree_does(
      make_box(half),
      [half](std::mt19937_64& generator) {
        std::uniform_real_distribution<double> uniform(-1.0, 1.0);
        return Vec3(half.x() * uniform(generator), half.y() * uniform(generator),
                    half.z() * uniform(generator));
      },
      20000);
}

TEST(ConvexCrossing, LeavesARoundedTileWhereEmbreeSays) {
  leaves_where_embree_does(make_rounded_tile(2.0, 1.5, 0.4, 0.3, 40, 64), in_ball(0.39), 20000);
}

TEST(ConvexCrossing, EntersAUvSphereWhereEmbreeDoes) {
  enters_where_embree_does(make_sphere(10.0, 49, 96, false), 20000, 7000);
}

TEST(ConvexCrossing, EntersABoxAndATileWhereEmbreeDoes) {
  enters_where_embree_does(make_box(Vec3(1.0, 2.0, 0.5)), 20000, 2000);
  enters_where_embree_does(make_rounded_tile(2.0, 1.5, 0.4, 0.3, 40, 64), 20000, 7000);
}

TEST(ConvexCrossing, ItsCoreLiesInsideAndTouchesTheSurface) {
  // The core is the ball about the centroid that the lanes pass flights into without a walk:
  // no ray from the centroid meets the surface inside it, and some come within 1e-4 of it (the
  // planes of the sphere's 9 216 facets, chords of about pi / 48 each way, come within about
  // 10 cos^2(pi / 96) = 9.989 of its centre).
  const TriangleMesh mesh = make_sphere(10.0, 49, 96, false);
  const MeshRayTracer tracer(mesh);
  const ConvexCrossing walk(mesh, tracer);
  EXPECT_LT(walk.centroid().norm(), 1e-9);
  EXPECT_GT(walk.inner_radius(), 9.98);
  std::mt19937_64 generator(17);
  double nearest = std::numeric_limits<double>::infinity();
  for (int ray = 0; ray < 200000; ++ray) {
    MeshHit hit;
    ASSERT_TRUE(tracer.intersect(walk.centroid(), random_direction(generator), 0.0,
                                 std::numeric_limits<double>::infinity(), hit));
    nearest = std::min(nearest, hit.distance);
  }
  EXPECT_GE(nearest, walk.inner_radius() * (1.0 - 1e-6));  // Embree's single precision
  EXPECT_LT(nearest, walk.inner_radius() * (1.0 + 1e-4));
}

TEST(ConvexCrossing, CrossesALongBarFarFromWhereTheWalkStarts) {
  // The ball about a 20 x 1 x 0.4 bar is a poor guess of where its rays cross: the walks run
  // along the bar.
  const Vec3 half(10.0, 0.5, 0.2);
  const TriangleMesh bar = make_rounded_tile(half.x(), half.y(), half.z(), 0.2, 30, 200);
  leaves_where_embree_does(
      bar,
      [half](std::mt19937_64& generator) {
        std::uniform_real_distribution<double> uniform(-0.7, 0.7);
        return Vec3(half.x() * uniform(generator), half.y() * uniform(generator),
                    half.z() * uniform(generator));
      },
      5000);
  enters_where_embree_does(bar, 5000, 150);
}

}  // namespace
}  // namespace scatterlab
