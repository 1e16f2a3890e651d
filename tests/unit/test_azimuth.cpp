// The azimuth's polynomial sine and cosine agree with the library's to rounding, over the whole
// turn and at the quadrant seams.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scatterlab/core/azimuth.hpp"

namespace scatterlab {
namespace {

TEST(Azimuth, MatchesLibrarySineAndCosine) {
  const int n = 1000003;
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    const double u = (i + 0.5) / n;
    const UnitCircle c = azimuth(u);
    const long double phi = 2.0L * std::numbers::pi_v<long double> * u;
    worst = std::max({worst, std::abs(c.cos - static_cast<double>(std::cos(phi))),
                      std::abs(c.sin - static_cast<double>(std::sin(phi)))});
  }
  EXPECT_LT(worst, 4e-16);
}

TEST(Azimuth, QuadrantSeamsAndUnitLength) {
  for (double u : {0.0, 0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875, 1.0 - 0x1p-33}) {
    for (double du : {-1e-12, 0.0, 1e-12}) {
      const double v = std::clamp(u + du, 0.0, 1.0 - 0x1p-33);
      const UnitCircle c = azimuth(v);
      EXPECT_NEAR(c.cos * c.cos + c.sin * c.sin, 1.0, 1e-15) << v;
      // The reference angle in long double: 2 pi v in double is itself off by ~4e-16 near 1.
      const long double phi = 2.0L * std::numbers::pi_v<long double> * v;
      EXPECT_NEAR(c.cos, static_cast<double>(std::cos(phi)), 4e-16) << v;
      EXPECT_NEAR(c.sin, static_cast<double>(std::sin(phi)), 4e-16) << v;
    }
  }
}

}  // namespace
}  // namespace scatterlab
