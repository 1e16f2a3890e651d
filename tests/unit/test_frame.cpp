// Orthonormal frames stay orthonormal everywhere, the poles included, and direction updates
// turn by exactly the requested angle.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/frame.hpp"
#include "scatterlab/core/random.hpp"

namespace scatterlab {
namespace {

void expect_orthonormal(const Vec3& n) {
  const Frame f(n);
  constexpr double tol = 1e-14;
  EXPECT_NEAR(f.tangent.norm(), 1.0, tol);
  EXPECT_NEAR(f.bitangent.norm(), 1.0, tol);
  EXPECT_NEAR(f.tangent.dot(f.bitangent), 0.0, tol);
  EXPECT_NEAR(f.tangent.dot(n), 0.0, tol);
  EXPECT_NEAR(f.bitangent.dot(n), 0.0, tol);
  EXPECT_NEAR((f.tangent.cross(f.bitangent) - n).norm(), 0.0, 1e-14) << n.transpose();
}

TEST(Frame, OrthonormalAtAndNearThePoles) {
  for (double z : {1.0, -1.0}) expect_orthonormal(Vec3(0, 0, z));
  for (double eps : {1e-300, 1e-16, 1e-8, 1e-3}) {
    for (double z : {1.0, -1.0}) {
      expect_orthonormal(Vec3(eps, 0, z * std::sqrt(1 - eps * eps)));
      expect_orthonormal(Vec3(0, -eps, z * std::sqrt(1 - eps * eps)));
    }
  }
  expect_orthonormal(Vec3(1, 0, 0));
  expect_orthonormal(Vec3(0, 0, -0.0).normalized() + Vec3(0, 1, 0));
}

TEST(Frame, OrthonormalForRandomDirections) {
  PhotonRandom random(7, 0);
  for (int i = 0; i < 10000; ++i) {
    const auto u = random.next4();
    expect_orthonormal(isotropic_direction(u[0], u[1]));
  }
}

TEST(Frame, ScatteringTurnsByTheRequestedAngle) {
  PhotonRandom random(11, 0);
  Vec3 direction = Vec3::UnitZ();
  // A long chain of updates, as in a photon with albedo near 1: no drift off the unit sphere.
  for (int i = 0; i < 100000; ++i) {
    const auto u = random.next4();
    const double cos_theta = 2.0 * u[0] - 1.0;
    const double phi = 2.0 * pi * u[1];
    const Vec3 next = scatter_direction(direction, cos_theta, std::cos(phi), std::sin(phi));
    ASSERT_NEAR(next.norm(), 1.0, 3e-16);
    ASSERT_NEAR(next.dot(direction), cos_theta, 1e-13);
    direction = next;
  }
}

}  // namespace
}  // namespace scatterlab
