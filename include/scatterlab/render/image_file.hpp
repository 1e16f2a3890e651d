#pragma once
// The two outputs of an image of linear radiance (io/image.hpp): OpenEXR (linear, 32-bit float, the
// value in R, G and B) and an 8-bit PNG for viewing, value * 2^exposure then ^(1 / gamma),
// clamped to [0, 1]. Both are written atomically (a temporary file renamed into place).

#include <filesystem>

#include "scatterlab/io/image.hpp"

namespace scatterlab {

// Throws InputError("out", ...) for an unwritable place, std::runtime_error on write failure.
void write_exr(const Image& image, const std::filesystem::path& path);
// gamma > 0; throws InputError("gamma", ...) otherwise.
void write_png(const Image& image, const std::filesystem::path& path, double exposure,
               double gamma);

}  // namespace scatterlab
