// FOM = 1 / (R^2 T) (MCNP5 manual, LA-UR-03-1987, ch. 2 §VI.D), R the relative standard error:
// of a scalar, or the median over a grid's bins that scored.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "scatterlab/tally/figure_of_merit.hpp"

namespace scatterlab {
namespace {

TEST(FigureOfMerit, OneOverRelativeVarianceTimesTime) {
  const std::vector<double> mean = {0.5}, error = {0.005};  // R = 0.01
  const double r = relative_standard_error(mean, error);
  EXPECT_DOUBLE_EQ(r, 0.01);
  EXPECT_DOUBLE_EQ(figure_of_merit(r, 2.0), 5000.0);
}

TEST(FigureOfMerit, GridTakesTheMedianOfBinsThatScored) {
  // Relative errors 0.1, 0.3, 0.2, 0.4; the empty bin is left out: median 0.25.
  const std::vector<double> mean = {1.0, -2.0, 0.0, 1.0, 0.5};
  const std::vector<double> error = {0.1, 0.6, 7.0, 0.2, 0.2};
  EXPECT_DOUBLE_EQ(relative_standard_error(mean, error), 0.25);
}

TEST(FigureOfMerit, UndefinedWithoutAnErrorOrTime) {
  const std::vector<double> nothing = {0.0, 0.0};
  EXPECT_TRUE(std::isnan(relative_standard_error(nothing, nothing)));
  EXPECT_TRUE(std::isnan(figure_of_merit(0.0, 1.0)));
  EXPECT_TRUE(std::isnan(figure_of_merit(0.1, 0.0)));
  EXPECT_TRUE(std::isnan(figure_of_merit(std::nan(""), 1.0)));
}

}  // namespace
}  // namespace scatterlab
