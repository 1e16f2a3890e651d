#include "scatterlab/render/image_file.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/atomic_output.hpp"

namespace scatterlab {

// Both formats are encoded in memory and written whole (write_whole_file), so that a write that
// fails is one error with the system's reason, whichever library encoded the image.

void write_exr(const Image& image, const std::filesystem::path& path) {
  AtomicOutput output(path);
  std::vector<float> pixels(image.values.size());
  std::transform(image.values.begin(), image.values.end(), pixels.begin(),
                 [](double v) { return static_cast<float>(v); });
  Imf::StdOSStream encoded;
  try {
    Imf::Header header(image.width, image.height);
    for (const char* name : {"R", "G", "B"})
      header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    Imf::OutputFile file(encoded, header);
    Imf::FrameBuffer frame;
    auto* base = reinterpret_cast<char*>(pixels.data());
    for (const char* name : {"R", "G", "B"}) {
      frame.insert(name, Imf::Slice(Imf::FLOAT, base, sizeof(float),
                                    sizeof(float) * static_cast<std::size_t>(image.width)));
    }
    file.setFrameBuffer(frame);
    file.writePixels(image.height);
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot write '" + path.string() + "': " + e.what());
  }
  write_whole_file(output.temporary_path(), encoded.str());
  output.commit();
}

namespace {

void append_to_buffer(png_structp png, png_bytep data, png_size_t length) {
  auto* buffer = static_cast<std::vector<char>*>(png_get_io_ptr(png));
  buffer->insert(buffer->end(), reinterpret_cast<const char*>(data),
                 reinterpret_cast<const char*>(data) + length);
}

void flush_nothing(png_structp) {}

}  // namespace

void write_png(const Image& image, const std::filesystem::path& path, double exposure,
               double gamma) {
  if (!(gamma > 0.0) || !std::isfinite(gamma)) {
    throw InputError("gamma", "got " + std::to_string(gamma), "a finite number > 0");
  }
  if (!std::isfinite(exposure)) {
    throw InputError("exposure", "got " + std::to_string(exposure), "a finite number (stops)");
  }
  AtomicOutput output(path);
  const double scale = std::exp2(exposure);
  std::vector<png_byte> rows(static_cast<std::size_t>(image.width) * image.height);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const double v =
        std::clamp(std::pow(std::max(image.values[k] * scale, 0.0), 1.0 / gamma), 0.0, 1.0);
    rows[k] = static_cast<png_byte>(std::lround(255.0 * (std::isfinite(v) ? v : 0.0)));
  }
  std::vector<char> encoded;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png != nullptr ? png_create_info_struct(png) : nullptr;
  if (png == nullptr || info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("libpng: cannot encode '" + path.string() + "'");
  }
  png_set_write_fn(png, &encoded, append_to_buffer, flush_nothing);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
               static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int j = 0; j < image.height; ++j) {
    png_write_row(png, rows.data() + static_cast<std::size_t>(j) * image.width);
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  write_whole_file(output.temporary_path(), encoded);
  output.commit();
}

}  // namespace scatterlab
