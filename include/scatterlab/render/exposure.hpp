#pragma once
// An exposure that shows an image: the stops that map a high percentile of its pixels to white,
// so that a few bright pixels (the light itself, a caustic) clip and the rest of the picture
// keeps its range. A fixed exposure suits no scene: the radiance scales with the light's
// intensity and the scene's size.

#include "scatterlab/io/image.hpp"

namespace scatterlab {

// The fraction of pixels at or below the level that maps to white.
inline constexpr double auto_exposure_percentile = 0.99;

// -log2 of the `percentile` of the pixel values (for an RgbImage, of each pixel's largest
// channel), taken over the pixels above zero so that a black background does not darken the
// object; 0 for an image without any.
double auto_exposure(const Image& image, double percentile = auto_exposure_percentile);
double auto_exposure(const RgbImage& image, double percentile = auto_exposure_percentile);

}  // namespace scatterlab
