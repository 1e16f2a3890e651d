// Henyey-Greenstein evaluation and sampling: normalisation, agreement with the textbook
// inversion, stability as g -> 0 and |g| -> 1, a chi-square test of the sampled density and the
// mean cosine (fixed seeds; tolerances stated).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/phase_function.hpp"
#include "scatterlab/core/random.hpp"

namespace scatterlab {
namespace {

// The HG cumulative distribution in mu, in long double:
//   P(mu) = (1 - g^2) / (2 g) [ (1 + g^2 - 2 g mu)^{-1/2} - 1 / (1 + g) ].
long double hg_cdf(long double g, long double mu) {
  if (g == 0.0L) return 0.5L * (mu + 1.0L);
  return (1.0L - g * g) / (2.0L * g) *
         (1.0L / std::sqrt(1.0L + g * g - 2.0L * g * mu) - 1.0L / (1.0L + g));
}

class HenyeyGreensteinTest : public ::testing::TestWithParam<double> {};

TEST_P(HenyeyGreensteinTest, DensityIntegratesToOne) {
  // 2 pi * integral of p over mu, with a substitution that follows the forward peak:
  // Simpson's rule on the CDF variable is exact for the density's own inverse, so instead
  // integrate p(mu) on a grid graded towards mu = sign(g) with 2e5 panels.
  const HenyeyGreenstein hg{GetParam()};
  const int panels = 200000;
  double integral = 0.0;
  for (int i = 0; i < panels; ++i) {
    // t in [0, 1] maps to mu = 1 - 2 t^4 (graded towards the peak at mu = 1); mirror for g < 0.
    auto mu_of = [&](double t) { return std::copysign(1.0, hg.g) * (1.0 - 2.0 * std::pow(t, 4)); };
    const double t0 = double(i) / panels, t1 = double(i + 1) / panels, tm = 0.5 * (t0 + t1);
    const double dmu_dt = 8.0 * std::pow(tm, 3);
    integral += 2.0 * pi * hg.evaluate(mu_of(tm)) * dmu_dt * (t1 - t0);
  }
  EXPECT_NEAR(integral, 1.0, 2e-4);
}

TEST_P(HenyeyGreensteinTest, SamplesFollowTheDensity) {
  // Chi-square over 50 cells equiprobable under the exact CDF; 1e6 samples. The critical value
  // for 49 degrees of freedom at p = 1e-4 is 93.0.
  const double g = GetParam();
  const HenyeyGreenstein hg{g};
  PhotonRandom random(12345, 0);
  const int samples = 1000000, cells = 50;
  std::vector<int> counts(cells, 0);
  double sum = 0.0;
  for (int i = 0; i < samples / 4; ++i) {
    for (double xi : random.next4()) {
      const double mu = hg.sample_cos_theta(xi);
      ASSERT_TRUE(mu >= -1.0 && mu <= 1.0) << mu;
      sum += mu;
      const long double u = hg_cdf(g, mu);
      counts[std::min(cells - 1, static_cast<int>(u * cells))]++;
    }
  }
  const double expected = double(samples) / cells;
  double chi2 = 0.0;
  for (int c : counts) chi2 += (c - expected) * (c - expected) / expected;
  EXPECT_LT(chi2, 93.0);

  // Mean cosine: Var(mu) = E[mu^2] - g^2 = (1 + 2 g^2) / 3 - g^2 = (1 - g^2) / 3 for HG.
  const double mean = sum / samples;
  const double sigma = std::sqrt((1.0 - g * g) / 3.0 / samples);
  EXPECT_NEAR(mean, hg.mean_cosine(), 5.0 * sigma);
}

TEST_P(HenyeyGreensteinTest, SamplingAgreesWithTextbookInversion) {
  // mu = (1 + g^2 - ((1 - g^2) / (1 - g + 2 g xi))^2) / (2 g), evaluated in long double.
  const double g = GetParam();
  if (g == 0.0) GTEST_SKIP() << "the textbook form divides by g";
  const HenyeyGreenstein hg{g};
  for (double xi : {1e-9, 0.001, 0.1, 0.25, 0.5, 0.75, 0.9, 0.999, 1.0 - 1e-9}) {
    const long double G = g;
    const long double t = (1.0L - G * G) / (1.0L - G + 2.0L * G * xi);
    const long double mu = (1.0L + G * G - t * t) / (2.0L * G);
    EXPECT_NEAR(hg.sample_cos_theta(xi), static_cast<double>(mu), 1e-12) << "xi = " << xi;
  }
}

INSTANTIATE_TEST_SUITE_P(Anisotropies, HenyeyGreensteinTest,
                         ::testing::Values(-0.99, 0.0, 0.3, 0.99, -0.999, 0.999));

TEST(HenyeyGreenstein, TinyAnisotropyIsIsotropicToFirstOrder) {
  // For |g| -> 0, mu = s + (3/2) g (1 - s^2) + O(g^2) with s = 2 xi - 1: no loss of precision.
  for (double g : {1e-9, -1e-9, 1e-300}) {
    const HenyeyGreenstein hg{g};
    for (double xi : {0.01, 0.3, 0.5, 0.8}) {
      const double s = 2.0 * xi - 1.0;
      EXPECT_NEAR(hg.sample_cos_theta(xi), s + 1.5 * g * (1.0 - s * s), 1e-15) << g;
      EXPECT_NEAR(hg.evaluate(0.3), inv_four_pi, 1e-8);
    }
  }
}

TEST(HenyeyGreenstein, ExtremeForwardPeakStaysFinite) {
  const HenyeyGreenstein hg{0.999999};
  EXPECT_TRUE(std::isfinite(hg.evaluate(1.0)));
  EXPECT_NEAR(hg.sample_cos_theta(0.5), 1.0, 1e-5);
  EXPECT_GE(hg.sample_cos_theta(1e-10), -1.0);
}

}  // namespace
}  // namespace scatterlab
