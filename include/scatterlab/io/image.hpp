#pragma once
// Images of linear radiance: what the renderer makes (render/image_file.hpp writes them as
// OpenEXR and PNG) and what a figure shows side by side (io/plot.hpp, ImageFigure). `Image` is one
// channel (the single-scatter methods render one); `RgbImage` is three of the same size, red,
// green and blue (a medium given per channel renders each).

#include <array>
#include <cstddef>
#include <vector>

namespace scatterlab {

struct Image {
  int width = 0, height = 0;
  std::vector<double> values;  // row-major, row 0 on top

  Image() = default;
  Image(int w, int h) : width(w), height(h), values(static_cast<std::size_t>(w) * h, 0.0) {}
  double& at(int i, int j) { return values[static_cast<std::size_t>(j) * width + i]; }
  double at(int i, int j) const { return values[static_cast<std::size_t>(j) * width + i]; }
};

struct RgbImage {
  std::array<Image, 3> channels;  // red, green, blue

  RgbImage() = default;
  RgbImage(int w, int h) : channels{Image(w, h), Image(w, h), Image(w, h)} {}
  // The same values in all three channels: a grey image.
  static RgbImage grey(const Image& image) { return from_channels(image, image, image); }
  static RgbImage from_channels(const Image& red, const Image& green, const Image& blue) {
    RgbImage rgb;
    rgb.channels = {red, green, blue};
    return rgb;
  }
  int width() const { return channels[0].width; }
  int height() const { return channels[0].height; }
};

}  // namespace scatterlab
