#include "scatterlab/render/image_file.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>
#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/atomic_output.hpp"

namespace scatterlab {

// Both formats are encoded in memory and written whole (write_whole_file), so that a write that
// fails is one error with the system's reason, whichever library encoded the image.

void write_exr(const RgbImage& image, const std::filesystem::path& path) {
  AtomicOutput output(path);
  const std::size_t count = image.channels[0].values.size();
  std::array<std::vector<float>, 3> pixels;
  for (std::size_t c = 0; c < 3; ++c) {
    pixels[c].resize(count);
    std::transform(image.channels[c].values.begin(), image.channels[c].values.end(),
                   pixels[c].begin(), [](double v) { return static_cast<float>(v); });
  }
  const std::array<const char*, 3> names{"R", "G", "B"};
  Imf::StdOSStream encoded;
  try {
    Imf::Header header(image.width(), image.height());
    for (const char* name : names) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    Imf::OutputFile file(encoded, header);
    Imf::FrameBuffer frame;
    for (std::size_t c = 0; c < 3; ++c) {
      auto* base = reinterpret_cast<char*>(pixels[c].data());
      frame.insert(names[c], Imf::Slice(Imf::FLOAT, base, sizeof(float),
                                        sizeof(float) * static_cast<std::size_t>(image.width())));
    }
    file.setFrameBuffer(frame);
    file.writePixels(image.height());
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot write '" + path.string() + "': " + e.what());
  }
  write_whole_file(output.temporary_path(), encoded.str());
  output.commit();
}

void write_exr(const Image& image, const std::filesystem::path& path) {
  write_exr(RgbImage::grey(image), path);
}

namespace {

void append_to_buffer(png_structp png, png_bytep data, png_size_t length) {
  auto* buffer = static_cast<std::vector<char>*>(png_get_io_ptr(png));
  buffer->insert(buffer->end(), reinterpret_cast<const char*>(data),
                 reinterpret_cast<const char*>(data) + length);
}

void flush_nothing(png_structp) {}

// 8-bit samples, `components` per pixel (1: grey, 3: RGB), rows from the top.
void encode_png(const std::vector<png_byte>& samples, int width, int height, int components,
                const std::filesystem::path& path) {
  AtomicOutput output(path);
  std::vector<char> encoded;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png != nullptr ? png_create_info_struct(png) : nullptr;
  if (png == nullptr || info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("libpng: cannot encode '" + path.string() + "'");
  }
  png_set_write_fn(png, &encoded, append_to_buffer, flush_nothing);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               components == 3 ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  const std::size_t row = static_cast<std::size_t>(width) * static_cast<std::size_t>(components);
  for (int j = 0; j < height; ++j) {
    png_write_row(png, const_cast<png_bytep>(samples.data() + static_cast<std::size_t>(j) * row));
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  write_whole_file(output.temporary_path(), encoded);
  output.commit();
}

void check_tone(double exposure, double gamma) {
  if (!(gamma > 0.0) || !std::isfinite(gamma)) {
    throw InputError("gamma", "got " + std::to_string(gamma), "a finite number > 0");
  }
  if (!std::isfinite(exposure)) {
    throw InputError("exposure", "got " + std::to_string(exposure), "a finite number (stops)");
  }
}

// value * 2^exposure, then ^(1 / gamma), clamped to [0, 1], as an 8-bit level.
png_byte tone(double value, double scale, double gamma) {
  const double v = std::clamp(std::pow(std::max(value * scale, 0.0), 1.0 / gamma), 0.0, 1.0);
  return static_cast<png_byte>(std::lround(255.0 * (std::isfinite(v) ? v : 0.0)));
}

}  // namespace

void write_png(const Image& image, const std::filesystem::path& path, double exposure,
               double gamma) {
  check_tone(exposure, gamma);
  const double scale = std::exp2(exposure);
  std::vector<png_byte> samples(image.values.size());
  for (std::size_t k = 0; k < samples.size(); ++k) samples[k] = tone(image.values[k], scale, gamma);
  encode_png(samples, image.width, image.height, 1, path);
}

void write_png(const RgbImage& image, const std::filesystem::path& path, double exposure,
               double gamma) {
  check_tone(exposure, gamma);
  const double scale = std::exp2(exposure);
  const std::size_t count = image.channels[0].values.size();
  std::vector<png_byte> samples(3 * count);
  for (std::size_t k = 0; k < count; ++k) {
    for (std::size_t c = 0; c < 3; ++c) {
      samples[3 * k + c] = tone(image.channels[c].values[k], scale, gamma);
    }
  }
  encode_png(samples, image.width(), image.height(), 3, path);
}

}  // namespace scatterlab
