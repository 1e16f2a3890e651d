// PNG line plots and image figures: a valid PNG of the asked size with drawn content on every
// axis scale, several at once, nothing left behind on bad input, and a message that says what to
// install when python3 or matplotlib is missing.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
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

void expect_png(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height,
                std::size_t least_bytes = 10000) {
  const auto bytes = read_bytes(path);
  // A blank 640 x 480 PNG compresses to about 2 kB; axes, text and curves take several times that.
  ASSERT_GT(bytes.size(), least_bytes) << path;
  // PNG signature, then the IHDR chunk with width and height (PNG spec §5.2, §11.2.2).
  const std::vector<unsigned char> signature{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  EXPECT_TRUE(std::equal(signature.begin(), signature.end(), bytes.begin()));
  EXPECT_EQ(std::string(bytes.begin() + 12, bytes.begin() + 16), "IHDR");
  EXPECT_EQ(big_endian(bytes, 16), width);
  EXPECT_EQ(big_endian(bytes, 20), height);
}

// Sets $SCATTERLAB_PYTHON for one test and restores it.
class PythonOverride {
 public:
  explicit PythonOverride(const std::string& program) {
    const char* old = std::getenv("SCATTERLAB_PYTHON");
    if (old != nullptr) old_ = old;
    had_ = old != nullptr;
    ::setenv("SCATTERLAB_PYTHON", program.c_str(), 1);
  }
  ~PythonOverride() {
    if (had_) {
      ::setenv("SCATTERLAB_PYTHON", old_.c_str(), 1);
    } else {
      ::unsetenv("SCATTERLAB_PYTHON");
    }
  }
  PythonOverride(const PythonOverride&) = delete;
  PythonOverride& operator=(const PythonOverride&) = delete;

 private:
  std::string old_;
  bool had_ = false;
};

LinePlot small_plot() {
  LinePlot plot;
  plot.title = "test";
  plot.series = {{"model", {1.0, 2.0, 3.0}, {1.0, 0.5, 0.25}, {}, false, "exact"}};
  return plot;
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
    plot.series = {{"Monte Carlo ±1σ", x, y, e, true, "monte_carlo"},
                   {"model", x, y, {}, false, "dipole"},
                   {"a model with no style key", x, y, {}, false}};
    const auto path = dir / ("plot_" + to_string(scale) + ".png");
    write_png(plot, path);
    expect_png(path, 640, 480);
  }
  // A log x axis, and points no axis can show (NaN, x <= 0 on the log axis) left out.
  LinePlot gaps = small_plot();
  gaps.log_x = true;
  gaps.y_scale = AxisScale::log;
  gaps.series.push_back({"gaps",
                         {0.0, 1.0, 2.0, 3.0},
                         {1.0, NAN, 0.5, 0.1},
                         {0.1, 0.1, 0.1, 1.0},
                         true,
                         "monte_carlo"});
  write_png(gaps, dir / "gaps.png");
  expect_png(dir / "gaps.png", 1050, 600);
  // A log plot of values that are all <= 0 has nothing to draw: an error, and no file.
  LinePlot empty;
  empty.y_scale = AxisScale::log;
  empty.series = {{"zero", {1.0, 2.0}, {0.0, -1.0}, {}, false}};
  EXPECT_THROW(write_png(empty, dir / "empty.png"), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "empty.png"));
  LinePlot mismatched;
  mismatched.series = {{"bad", {1.0, 2.0}, {1.0}, {}, false}};
  EXPECT_THROW(write_png(mismatched, dir / "bad.png"), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.png"));
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << entry.path();
  }
  std::filesystem::remove_all(dir);
}

TEST(Plot, WritesSeveralPlotsAndChecksThemAllFirst) {
  const auto dir = std::filesystem::temp_directory_path() / "scatterlab_test_plots";
  std::filesystem::create_directories(dir);
  write_pngs({{small_plot(), dir / "a.png"}, {small_plot(), dir / "b.png"}});
  expect_png(dir / "a.png", 1050, 600);
  expect_png(dir / "b.png", 1050, 600);
  // One bad plot: nothing is written, not even the good one before it.
  LinePlot bad;
  EXPECT_THROW(write_pngs({{small_plot(), dir / "c.png"}, {bad, dir / "d.png"}}), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "c.png"));
  std::filesystem::remove_all(dir);
}

TEST(Plot, WritesTitledImagesSideBySide) {
  const auto dir = std::filesystem::temp_directory_path() / "scatterlab_test_plot_images";
  std::filesystem::create_directories(dir);
  Image a(8, 8), b(8, 8), other(4, 8);
  for (int j = 0; j < 8; ++j) {
    for (int i = 0; i < 8; ++i) a.at(i, j) = b.at(7 - i, j) = 0.1 * i;
  }
  ImageFigure figure;
  figure.title = "images";
  figure.width = 600;
  figure.height = 300;
  figure.panels = {{"reference", &a}, {"method\nbudget", &b}};
  write_png(figure, dir / "images.png");
  expect_png(dir / "images.png", 600, 300, 4000);
  // Panels of different sizes, a missing image, no panel: refused, nothing written.
  figure.panels.push_back({"other", &other});
  EXPECT_THROW(write_png(figure, dir / "bad.png"), InputError);
  figure.panels.back().image = nullptr;
  EXPECT_THROW(write_png(figure, dir / "bad.png"), InputError);
  figure.panels.clear();
  EXPECT_THROW(write_png(figure, dir / "bad.png"), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.png"));
  std::filesystem::remove_all(dir);
}

TEST(Plot, SaysWhatToInstallWithoutPythonOrMatplotlib) {
  const auto dir = std::filesystem::temp_directory_path() / "scatterlab_test_plot_python";
  std::filesystem::create_directories(dir);
  // write_png, and require_plotting, which commands call before their work.
  const auto expect_install_message = [&](const std::string& why) {
    for (const bool drawing : {true, false}) {
      try {
        if (drawing) {
          write_png(small_plot(), dir / "p.png");
        } else {
          require_plotting();
        }
        ADD_FAILURE() << why << ": no error";
      } catch (const std::runtime_error& error) {
        EXPECT_NE(std::string(error.what())
                      .find("figures need python3 with matplotlib (Debian: "
                            "python3-matplotlib)"),
                  std::string::npos)
            << why << ": " << error.what();
      }
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "p.png")) << why;
  };
  EXPECT_NO_THROW(require_plotting());
  {
    const PythonOverride none((dir / "no-such-python3").string());
    expect_install_message("no python3");
  }
  // A python3 where importing matplotlib fails, as where it is not installed: the script's own
  // check answers. It runs the drawing script (-c SCRIPT [REQUEST]) with matplotlib blocked.
  if (::access("/usr/bin/python3", X_OK) == 0) {
    const auto wrapper = dir / "python3-without-matplotlib";
    std::ofstream(wrapper) << "#!/bin/sh\nexec /usr/bin/python3 -c \"import sys; "
                              "sys.modules['matplotlib'] = None\n$2\" ${3+\"$3\"}\n";
    std::filesystem::permissions(wrapper, std::filesystem::perms::owner_all);
    const PythonOverride blocked(wrapper.string());
    expect_install_message("no matplotlib");
  }
  // A bad plot is refused before python3 is looked for.
  {
    const PythonOverride none((dir / "no-such-python3").string());
    LinePlot empty;
    EXPECT_THROW(write_png(empty, dir / "p.png"), InputError);
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace scatterlab
