#pragma once
// The two outputs of an image of linear radiance (io/image.hpp): OpenEXR (linear, 32-bit float,
// R, G and B; a one-channel Image puts its value in all three) and an 8-bit PNG for viewing,
// value * 2^exposure then ^(1 / gamma), clamped to [0, 1] (grey for an Image, RGB for an
// RgbImage). Both are written atomically (a temporary file renamed into place).

#include <filesystem>

#include "scatterlab/io/image.hpp"

namespace scatterlab {

// Throws InputError("out", ...) for an unwritable place, std::runtime_error on write failure.
void write_exr(const Image& image, const std::filesystem::path& path);
void write_exr(const RgbImage& image, const std::filesystem::path& path);
// gamma > 0; throws InputError("gamma", ...) otherwise.
void write_png(const Image& image, const std::filesystem::path& path, double exposure,
               double gamma);
void write_png(const RgbImage& image, const std::filesystem::path& path, double exposure,
               double gamma);

}  // namespace scatterlab
