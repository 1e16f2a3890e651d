// The default exposure of render's PNG (render/exposure.hpp): the 99th percentile of the lit
// pixels maps to white, whatever the black background around them.
#include <gtest/gtest.h>

#include <cmath>

#include "scatterlab/render/exposure.hpp"

namespace scatterlab {
namespace {

TEST(AutoExposure, PercentileOfLitPixelsMapsToWhite) {
  Image image(20, 20);  // 400 pixels, 100 lit with 1 ... 100
  for (int k = 0; k < 100; ++k) image.values[static_cast<std::size_t>(k) * 4] = k + 1.0;
  // The 99th percentile of 100 values is the 99th smallest, k = floor(0.99 * 99) = 98: 99.
  EXPECT_DOUBLE_EQ(auto_exposure(image), -std::log2(99.0));
  // Scaling the radiance moves the exposure by as many stops: the PNG looks the same.
  for (double& v : image.values) v *= 8.0;
  EXPECT_DOUBLE_EQ(auto_exposure(image), -std::log2(99.0) - 3.0);
}

TEST(AutoExposure, RgbUsesEachPixelsBrightestChannel) {
  Image red(2, 1), green(2, 1), blue(2, 1);
  red.values = {4.0, 0.0};
  green.values = {1.0, 0.0};
  blue.values = {0.0, 2.0};
  // Lit pixels' maxima: 4 and 2; the 99th percentile of two is the smaller (k = 0).
  EXPECT_DOUBLE_EQ(auto_exposure(RgbImage::from_channels(red, green, blue)), -1.0);
}

TEST(AutoExposure, BlackImageKeepsZeroStops) {
  EXPECT_EQ(auto_exposure(Image(3, 3)), 0.0);
  EXPECT_EQ(auto_exposure(RgbImage(3, 3)), 0.0);
}

}  // namespace
}  // namespace scatterlab
