#pragma once
// A monochrome image of linear radiance: what the renderer makes (render/image_file.hpp writes it
// as OpenEXR and PNG) and what a figure shows side by side (io/plot.hpp, ImageFigure).

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

}  // namespace scatterlab
