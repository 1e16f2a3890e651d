// A photon's stream depends only on (seed, photon index).
#include <gtest/gtest.h>

#include <cmath>

#include "scatterlab/core/random.hpp"

namespace scatterlab {
namespace {

TEST(PhotonRandom, StreamIsAPureFunctionOfSeedAndPhoton) {
  PhotonRandom a(42, 1000), b(42, 1000), other_photon(42, 1001), other_seed(43, 1000);
  for (int i = 0; i < 100; ++i) {
    const auto x = a.next4(), y = b.next4(), z = other_photon.next4(), w = other_seed.next4();
    EXPECT_EQ(x, y);
    EXPECT_NE(x, z);
    EXPECT_NE(x, w);
  }
}

TEST(PhotonRandom, UniformsAreInsideTheOpenUnitInterval) {
  PhotonRandom random(1, 0);
  double sum = 0.0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    for (double u : random.next4()) {
      ASSERT_GT(u, 0.0);
      ASSERT_LT(u, 1.0);
      sum += u;
    }
  }
  // Mean of 4n uniforms: 1/2 with sigma sqrt(1/12 / 4n); 5 sigma.
  EXPECT_NEAR(sum / (4.0 * n), 0.5, 5.0 * std::sqrt(1.0 / 12.0 / (4.0 * n)));
}

TEST(PhotonRandom, HighPhotonIndicesDoNotAlias) {
  PhotonRandom low(5, 1), high(5, (std::uint64_t{1} << 32) + 1);
  EXPECT_NE(low.next4(), high.next4());
}

}  // namespace
}  // namespace scatterlab
