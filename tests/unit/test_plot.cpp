// PNG line plots: a valid PNG of the asked size on every axis scale, nothing left behind on
// bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/plot.hpp"

namespace scatterlab {
namespace {

std::vector<unsigned char> read_bytes(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

std::uint32_t big_endian(const std::vector<unsigned char>& b, std::size_t at) {
  return (std::uint32_t{b[at]} << 24) | (std::uint32_t{b[at + 1]} << 16) |
         (std::uint32_t{b[at + 2]} << 8) | std::uint32_t{b[at + 3]};
}

TEST(Plot, WritesAValidPngOnEveryScale) {
  const auto dir = std::filesystem::temp_directory_path() / "scatterlab_test_plot";
  std::filesystem::create_directories(dir);
  std::vector<double> x, y, e;
  for (int i = 0; i < 50; ++i) {
    x.push_back(0.1 * i);
    y.push_back(std::exp(-0.1 * i));
    e.push_back(0.01);
  }
  for (const AxisScale scale : {AxisScale::linear, AxisScale::log, AxisScale::sqrt}) {
    LinePlot plot;
    plot.title = "test";
    plot.x_label = "r";
    plot.y_label = "y";
    plot.y_scale = scale;
    plot.width = 640;
    plot.height = 480;
    plot.series = {{"Monte Carlo", x, y, e, true}, {"model", x, y, {}, false}};
    const auto path = dir / ("plot_" + to_string(scale) + ".png");
    write_png(plot, path);
    const auto bytes = read_bytes(path);
    ASSERT_GT(bytes.size(), 1000u);
    // PNG signature, then the IHDR chunk with width and height (PNG spec §5.2, §11.2.2).
    const std::vector<unsigned char> signature{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    EXPECT_TRUE(std::equal(signature.begin(), signature.end(), bytes.begin()));
    EXPECT_EQ(std::string(bytes.begin() + 12, bytes.begin() + 16), "IHDR");
    EXPECT_EQ(big_endian(bytes, 16), 640u);
    EXPECT_EQ(big_endian(bytes, 20), 480u);
  }
  // A log plot of values that are all <= 0 has nothing to draw: an error, and no file.
  LinePlot empty;
  empty.y_scale = AxisScale::log;
  empty.series = {{"zero", {1.0, 2.0}, {0.0, -1.0}, {}, false}};
  EXPECT_THROW(write_png(empty, dir / "empty.png"), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "empty.png"));
  LinePlot mismatched;
  mismatched.series = {{"bad", {1.0, 2.0}, {1.0}, {}, false}};
  EXPECT_THROW(write_png(mismatched, dir / "bad.png"), InputError);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace scatterlab
