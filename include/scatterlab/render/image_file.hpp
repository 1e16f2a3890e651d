#pragma once
// A monochrome image of linear radiance, and its two outputs: OpenEXR (linear, 32-bit float, the
// value in R, G and B) and an 8-bit PNG for viewing, value * 2^exposure then ^(1 / gamma),
// clamped to [0, 1]. Both are written atomically (a temporary file renamed into place).

#include <filesystem>
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

// Throws InputError("out", ...) for an unwritable place, std::runtime_error on write failure.
void write_exr(const Image& image, const std::filesystem::path& path);
// gamma > 0; throws InputError("gamma", ...) otherwise.
void write_png(const Image& image, const std::filesystem::path& path, double exposure,
               double gamma);

}  // namespace scatterlab
