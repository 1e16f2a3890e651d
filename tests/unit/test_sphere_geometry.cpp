// The sphere geometry (transport/sphere.hpp): under total internal reflection the whole chords
// of a flight are taken as one rotation about the centre; it must end where a bounce-by-bounce
// loop of mirror reflections ends, including near grazing incidence, where the loop takes
// 1 / cos theta_i bounces per mfp.
#include <gtest/gtest.h>

#include <cmath>

#include "scatterlab/core/frame.hpp"
#include "scatterlab/core/random.hpp"
#include "scatterlab/transport/sphere.hpp"

namespace scatterlab {
namespace {

struct Flight {
  Vec3 position, direction, next;
};

// Mirror reflections one by one until the flight ends inside (every hit totally reflected). Each
// hit is put back on the sphere: near grazing incidence the chord from a point off the sphere by
// rounding is ill-conditioned, and over 1e5 bounces the loop would drift by 1e-5.
Flight bounce_by_bounce(Vec3 position, Vec3 direction, double flight, double radius) {
  for (;;) {
    const double to_surface = distance_to_sphere(position, direction, radius);
    if (flight <= to_surface) return {position, direction, position + flight * direction};
    const Vec3 normal = (position + to_surface * direction).normalized();
    const Vec3 hit = radius * normal;
    direction = (direction - 2.0 * direction.dot(normal) * normal).normalized();
    position = hit;
    flight -= to_surface;
  }
}

TEST(SphereGeometry, TotalInternalReflectionTurnsAsTheBounceByBounceLoop) {
  const double radius = 2.0, eta = 1.5;  // inside, cos theta below sqrt(1 - 1/eta^2) = 0.745
  const Sphere<true> sphere(radius, eta);
  struct Case {
    double cos_incidence, flight;
    double tolerance;
  };
  // Flights that do not end within rounding of a whole number of chords (2 R cos theta_i), where
  // the two may stop one reflection apart at the same end point.
  for (const Case c : {Case{0.3, 7.3, 1e-12}, Case{0.7, 0.5, 1e-12}, Case{1e-5, 3.000013, 1e-8}}) {
    // A chord that meets the surface at (R, 0, 0) at cos theta_i, travelling towards +y and +z.
    const double sine = std::sqrt(1.0 - c.cos_incidence * c.cos_incidence);
    const Vec3 direction = Vec3(c.cos_incidence, 0.6 * sine, 0.8 * sine);
    const Vec3 hit(radius, 0.0, 0.0);
    const double before = 0.05 * radius * c.cos_incidence;  // inside, just short of the hit
    Vec3 position = hit - before * direction, heading = direction;
    Vec3 next = position + (before + c.flight) * heading;
    PhotonRandom random(1, 0);
    SurfaceExit exit;
    ASSERT_FALSE(sphere.leaves(position, heading, next, before + c.flight, random, exit));
    const Flight expected =
        bounce_by_bounce(hit - before * direction, direction, before + c.flight, radius);
    EXPECT_LT((next - expected.next).norm(), c.tolerance * radius) << c.cos_incidence;
    // Near grazing the loop's chords, each computed from a point rounded onto the sphere, drift
    // by 1e-6 of a chord each (a long double loop agrees with the rotation instead), so its last
    // point of reflection can lie part of a chord away on the same path: compare those only
    // where every chord is well conditioned.
    if (c.cos_incidence > 0.1) {
      EXPECT_LT((position - expected.position).norm(), c.tolerance * radius) << c.cos_incidence;
      EXPECT_LT((heading - expected.direction).norm(), c.tolerance) << c.cos_incidence;
    }
    EXPECT_LE(next.norm(), radius * (1.0 + 1e-12));
  }
}

}  // namespace
}  // namespace scatterlab
