// ExponentialSum against the same sum in libm's exp, term by term, on every instruction set.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "every_target.hpp"
#include "scatterlab/core/exponential_sum.hpp"

namespace scatterlab {
namespace {

TEST(ExponentialSum, MatchesTheScalarSumOnEveryTarget) {
  // 48 terms (not a multiple of any vector's lanes), rates from 1 to 1e6 as an escape rule's
  // 1 / mu spans, mixed-sign weights so that a dropped or doubled term cannot hide.
  std::vector<double> weights, rates;
  for (int k = 0; k < 48; ++k) {
    weights.push_back((k % 3 == 0 ? -1.0 : 1.0) * (1.0 + 0.1 * k));
    rates.push_back(std::pow(10.0, 6.0 * k / 47.0));
  }
  const ExponentialSum sum(weights, rates);
  for (const double x : {0.0, 1e-7, 1e-3, 0.3, 1.0, 7.5, 50.0, 800.0}) {
    double expected = 0.0, scale = 0.0;
    for (std::size_t k = 0; k < weights.size(); ++k) {
      expected += weights[k] * std::exp(-x * rates[k]);
      scale += std::abs(weights[k] * std::exp(-x * rates[k]));
    }
    testing::on_every_target([&] {
      // Each term within 1 ulp, added in another order: a few ulp of the terms' magnitudes.
      EXPECT_NEAR(sum(x), expected, 1e-15 * scale + 1e-300) << "x = " << x;
    });
  }
  EXPECT_EQ(ExponentialSum()(1.0), 0.0);  // no terms
}

TEST(ExponentialSum, RefusesUnpairedTerms) {
  const std::vector<double> two{1.0, 2.0}, one{1.0};
  EXPECT_THROW(ExponentialSum(two, one), std::invalid_argument);
}

}  // namespace
}  // namespace scatterlab
