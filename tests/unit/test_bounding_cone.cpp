// The cone bounds behind the refractive solver's pruning (refract/bounding_cone.hpp): each must
// hold every direction it claims to bound, checked on random directions drawn inside the input
// cones (fixed seeds). A bound that misses a direction would prune a real refracted path.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/refract/bounding_cone.hpp"

namespace scatterlab {
namespace {

// A direction within `cone` (uniform in angle up to the half-angle, uniform in azimuth).
Vec3 direction_in(const DirectionCone& cone, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Frame frame(cone.axis);
  const double theta = cone.half_angle * u(rng), phi = 2.0 * pi * u(rng);
  return frame.to_world(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                        std::cos(theta));
}

DirectionCone random_cone(std::mt19937_64& rng, double max_half_angle) {
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Vec3 axis = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
  return {axis, max_half_angle * u(rng) * u(rng)};  // many narrow cones, some wide
}

TEST(BoundingCone, ConeOfDirectionsHoldsEachAndIsTight) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 2000; ++trial) {
    const DirectionCone source = random_cone(rng, 1.2);
    std::vector<Vec3> directions;
    for (int k = 0; k < 6; ++k) directions.push_back(direction_in(source, rng));
    const DirectionCone cone = cone_of_directions(directions);
    ASSERT_FALSE(cone.is_none());
    if (cone.is_everything()) continue;
    double widest = 0.0;
    for (const Vec3& d : directions) {
      widest = std::max(widest, angle_between(cone.axis, d));
      EXPECT_LE(angle_between(cone.axis, d), cone.half_angle) << trial;
    }
    EXPECT_LE(cone.half_angle - widest, cosine_tie_slack + 1e-15) << trial;
  }
}

TEST(BoundingCone, BoxOfConeHoldsItsDirections) {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 2000; ++trial) {
    const DirectionCone cone = random_cone(rng, 1.5);
    const VectorBox box = box_of_cone(cone);
    for (int k = 0; k < 20; ++k) {
      const Vec3 d = direction_in(cone, rng);
      EXPECT_TRUE((d.array() >= box.lo.array()).all() && (d.array() <= box.hi.array()).all())
          << trial << ": " << d.transpose() << " outside [" << box.lo.transpose() << "], ["
          << box.hi.transpose() << "]";
    }
  }
}

// Light from directions in l_cone refracting through normals in a normal cone: every refracted
// direction lies in refracted_cone, and none() means no light entered.
TEST(BoundingCone, RefractedConeHoldsEveryRefractedDirection) {
  std::mt19937_64 rng(11);
  std::size_t refracted = 0, none_cones = 0;
  for (const double eta : {1.5, 2.5, 1.0001, 0.75, 0.4}) {
    for (int trial = 0; trial < 3000; ++trial) {
      const DirectionCone normals = random_cone(rng, 0.8);
      const DirectionCone l_cone = random_cone(rng, 0.6);
      const DirectionCone bound = refracted_cone(normals, l_cone, eta);
      none_cones += bound.is_none();
      for (int k = 0; k < 10; ++k) {
        const Vec3 n = direction_in(normals, rng);
        const Vec3 omega_l = direction_in(l_cone, rng);
        if (!(omega_l.dot(n) > 0.0)) continue;  // light behind the surface
        Vec3 t;
        if (!refract(-omega_l, n, eta, t)) continue;  // totally reflected
        ++refracted;
        ASSERT_FALSE(bound.is_none()) << "eta " << eta << " trial " << trial;
        if (bound.is_everything()) continue;
        EXPECT_LE(angle_between(bound.axis, t), bound.half_angle + 1e-12)
            << "eta " << eta << " trial " << trial;
      }
    }
  }
  EXPECT_GT(refracted, 50000u);
  EXPECT_GT(none_cones, 100u);  // the cases that prune whole parts occur
}

TEST(BoundingCone, RefractedConeOfOneRayIsThatRay) {
  const Vec3 n = Vec3(0.2, -0.1, 1.0).normalized();
  const Vec3 omega_l = Vec3(-0.5, 0.3, 0.8).normalized();
  Vec3 t;
  ASSERT_TRUE(refract(-omega_l, n, 1.5, t));
  const DirectionCone bound = refracted_cone({n, 0.0}, {omega_l, 0.0}, 1.5);
  EXPECT_LT(angle_between(bound.axis, t), 1e-6);
  EXPECT_LT(bound.half_angle, 1e-6);
  EXPECT_TRUE(refracted_cone({n, 0.0}, {-omega_l, 0.0}, 1.5).is_none());  // from behind
}

}  // namespace
}  // namespace scatterlab
