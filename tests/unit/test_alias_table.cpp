// The alias table (core/alias_table.hpp) draws each index with probability proportional to its
// weight: over a grid of a million evenly spaced u, each index's share is its weight's to 1e-5
// (the grid's resolution, two columns' coin edges each), an index of weight 0 is never drawn,
// and bad weights are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "scatterlab/core/alias_table.hpp"

namespace scatterlab {
namespace {

std::vector<double> shares(const AliasTable& table, int grid) {
  std::vector<double> count(table.size(), 0.0);
  for (int k = 0; k < grid; ++k) count[table.draw((k + 0.5) / grid)] += 1.0 / grid;
  return count;
}

TEST(AliasTable, DrawsEachIndexInProportionToItsWeight) {
  for (const std::vector<double>& weights :
       {std::vector<double>{1.0, 2.0, 3.0, 0.0, 4.0}, std::vector<double>{5.0},
        std::vector<double>{1e-9, 1.0, 1e9, 0.5, 0.5, 0.0, 7.0, 3.25}}) {
    const AliasTable table(weights);
    double total = 0.0;
    for (const double w : weights) total += w;
    const std::vector<double> drawn = shares(table, 1'000'000);
    for (std::size_t i = 0; i < weights.size(); ++i) {
      EXPECT_NEAR(drawn[i], weights[i] / total, 1e-5) << "index " << i;
      if (weights[i] == 0.0) {
        EXPECT_EQ(drawn[i], 0.0) << "index " << i;
      }
    }
  }
}

TEST(AliasTable, TheEndsOfTheUnitIntervalDrawValidIndices) {
  const AliasTable table({1.0, 0.0, 2.0});
  EXPECT_NE(table.draw(0.0), 1U);
  EXPECT_NE(table.draw(std::nextafter(1.0, 0.0)), 1U);
  EXPECT_LT(table.draw(std::nextafter(1.0, 0.0)), 3U);
}

TEST(AliasTable, RefusesWeightsThatDrawNothing) {
  EXPECT_THROW(AliasTable({}), std::invalid_argument);
  EXPECT_THROW(AliasTable({0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(AliasTable({1.0, -1.0}), std::invalid_argument);
  EXPECT_THROW(AliasTable({1.0, std::numeric_limits<double>::quiet_NaN()}), std::invalid_argument);
  EXPECT_THROW(AliasTable({1.0, std::numeric_limits<double>::infinity()}), std::invalid_argument);
}

}  // namespace
}  // namespace scatterlab
