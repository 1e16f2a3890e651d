#include "scatterlab/io/plot.hpp"

#include <plplot.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/atomic_output.hpp"

namespace scatterlab {
namespace {

// PLplot keeps global state per stream; one plot at a time.
std::mutex plplot_mutex;

// Distinct colours (Okabe-Ito), as PLplot colour-map-0 indices 1.., 0 being the background.
constexpr int palette[][3] = {{0, 0, 0},       {230, 159, 0},  {86, 180, 233}, {0, 158, 115},
                              {213, 94, 0},    {0, 114, 178},  {204, 121, 167}, {240, 228, 66},
                              {120, 120, 120}};
constexpr int palette_size = static_cast<int>(std::size(palette));

bool device_available(const char* name) {
  // plgDevs fills caller-owned arrays; the count goes in as their capacity.
  std::vector<const char*> menu(256), devices(256);
  int count = static_cast<int>(devices.size());
  const char** menu_data = menu.data();
  const char** device_data = devices.data();
  plgDevs(&menu_data, &device_data, &count);
  for (int i = 0; i < count; ++i) {
    if (devices[static_cast<std::size_t>(i)] != nullptr && std::string(devices[static_cast<std::size_t>(i)]) == name) return true;
  }
  return false;
}

// The y value as drawn: log10 on a log axis, sqrt on a sqrt axis; NaN where it cannot be shown.
double transform(double y, AxisScale scale) {
  if (!std::isfinite(y)) return std::numeric_limits<double>::quiet_NaN();
  switch (scale) {
    case AxisScale::log: return y > 0.0 ? std::log10(y) : std::numeric_limits<double>::quiet_NaN();
    case AxisScale::sqrt: return y >= 0.0 ? std::sqrt(y) : std::numeric_limits<double>::quiet_NaN();
    case AxisScale::linear: break;
  }
  return y;
}

// Tick labels of the sqrt axis show y, not sqrt(y).
void sqrt_axis_label(PLINT axis, PLFLT value, char* label, PLINT length, PLPointer) {
  if (axis == PL_Y_AXIS) {
    std::snprintf(label, static_cast<std::size_t>(length), "%.3g", value * value);
  } else {
    std::snprintf(label, static_cast<std::size_t>(length), "%.3g", value);
  }
}

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  }
  bool empty() const { return !(hi >= lo); }
  void pad(double fraction) {
    const double span = hi > lo ? hi - lo : std::max(std::abs(hi), 1.0);
    lo -= fraction * span;
    hi += fraction * span;
  }
};

void check(const LinePlot& plot) {
  if (plot.series.empty()) throw InputError("plot", "no series", "at least one series");
  for (const PlotSeries& s : plot.series) {
    if (s.x.size() != s.y.size() || (!s.y_error.empty() && s.y_error.size() != s.y.size())) {
      throw InputError("plot", "series \"" + s.name + "\" has mismatched lengths",
                       "x, y (and y_error if given) of equal length");
    }
  }
  if (plot.width < 100 || plot.height < 100) {
    throw InputError("plot", "size " + std::to_string(plot.width) + "x" + std::to_string(plot.height),
                     "at least 100 x 100 pixels");
  }
}

}  // namespace

std::string to_string(AxisScale scale) {
  switch (scale) {
    case AxisScale::linear: return "linear";
    case AxisScale::log: return "log";
    case AxisScale::sqrt: return "sqrt";
  }
  return "linear";
}

// The plot with x replaced by log10 x on a logarithmic x axis (x <= 0 becomes NaN: not drawn).
LinePlot with_drawn_x(const LinePlot& plot) {
  LinePlot drawn = plot;
  if (!plot.log_x) return drawn;
  for (PlotSeries& s : drawn.series) {
    for (double& x : s.x) x = x > 0.0 ? std::log10(x) : std::numeric_limits<double>::quiet_NaN();
  }
  return drawn;
}

void write_png(const LinePlot& requested, const std::filesystem::path& path) {
  check(requested);
  const LinePlot plot = with_drawn_x(requested);
  // Transformed copies and the drawn ranges.
  std::vector<std::vector<double>> ys(plot.series.size()), lows(plot.series.size()),
      highs(plot.series.size());
  Range xr, yr;
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    const PlotSeries& s = plot.series[k];
    for (std::size_t i = 0; i < s.y.size(); ++i) {
      const double y = transform(s.y[i], plot.y_scale);
      ys[k].push_back(y);
      if (!std::isfinite(y) || !std::isfinite(s.x[i])) continue;
      xr.add(s.x[i]);
      yr.add(y);
      if (!s.y_error.empty()) {
        const double low = transform(s.y[i] - s.y_error[i], plot.y_scale);
        const double high = transform(s.y[i] + s.y_error[i], plot.y_scale);
        lows[k].push_back(std::isfinite(low) ? low : y);
        highs[k].push_back(std::isfinite(high) ? high : y);
        yr.add(lows[k].back());
        yr.add(highs[k].back());
      }
    }
  }
  if (xr.empty() || yr.empty()) {
    throw InputError("plot", "no point can be drawn on a " + to_string(plot.y_scale) + " axis",
                     "at least one finite point (positive on a log axis)");
  }
  xr.pad(0.02);
  yr.pad(0.05);
  if (plot.y_scale == AxisScale::sqrt) yr.lo = std::max(yr.lo, 0.0);

  AtomicOutput output(path);
  // PLplot ignores a failed write of its PNG: it draws into memory (the stream plend1 closes),
  // and write_whole_file puts it on the disk, where a failure is reported.
  char* image = nullptr;
  std::size_t image_size = 0;
  {
    const std::lock_guard<std::mutex> lock(plplot_mutex);
    if (!device_available("pngcairo")) {
      throw std::runtime_error(
          "plot: PLplot has no pngcairo device (install plplot-driver-cairo)");
    }
    std::FILE* memory = open_memstream(&image, &image_size);
    if (memory == nullptr) throw std::runtime_error("plot: no memory for " + path.string());
    PLINT previous = 0, stream = 0;
    plgstrm(&previous);
    plmkstrm(&stream);
    plsdev("pngcairo");
    plsfile(memory);
    plspage(0.0, 0.0, plot.width, plot.height, 0, 0);
    plscolbg(255, 255, 255);
    for (int c = 0; c < palette_size; ++c) plscol0(c + 1, palette[c][0], palette[c][1], palette[c][2]);
    plinit();
    pladv(0);
    plvpor(0.10, 0.95, 0.10, 0.88);  // room above for the title and the axis exponent
    plwind(xr.lo, xr.hi, yr.lo, yr.hi);
    plcol0(1);
    if (plot.y_scale == AxisScale::sqrt) plslabelfunc(sqrt_axis_label, nullptr);
    const char* y_options = plot.y_scale == AxisScale::log    ? "bcnstlv"
                            : plot.y_scale == AxisScale::sqrt ? "bcnstov"
                                                              : "bcnstv";
    plbox(plot.log_x ? "bcnstl" : "bcnst", 0.0, 0, y_options, 0.0, 0);
    plslabelfunc(nullptr, nullptr);
    const std::string y_label =
        plot.y_label + (plot.y_scale == AxisScale::linear ? "" : " (" + to_string(plot.y_scale) + " scale)");
    pllab(plot.x_label.c_str(), y_label.c_str(), plot.title.c_str());

    std::vector<PLINT> opt(plot.series.size()), colours(plot.series.size()), styles(plot.series.size(), 1),
        symbol_numbers(plot.series.size(), 1);
    std::vector<PLFLT> widths(plot.series.size(), 2.0), symbol_scales(plot.series.size(), 1.0);
    std::vector<const char*> texts(plot.series.size()), symbols(plot.series.size());
    for (std::size_t k = 0; k < plot.series.size(); ++k) {
      const PlotSeries& s = plot.series[k];
      const PLINT colour = 2 + static_cast<PLINT>(k % (palette_size - 1));
      plcol0(colour);
      plwidth(2.0);
      if (s.markers) {
        std::vector<double> px, py;
        for (std::size_t i = 0; i < s.x.size(); ++i) {
          if (std::isfinite(ys[k][i]) && std::isfinite(s.x[i])) px.push_back(s.x[i]), py.push_back(ys[k][i]);
        }
        plstring(static_cast<PLINT>(px.size()), px.data(), py.data(), "#(728)");
        if (!s.y_error.empty() && !lows[k].empty()) {
          plwidth(1.0);
          plerry(static_cast<PLINT>(px.size()), px.data(), lows[k].data(), highs[k].data());
        }
      } else {
        // Draw each run of drawable points as one line.
        std::vector<double> px, py;
        const auto flush = [&] {
          if (px.size() >= 2) plline(static_cast<PLINT>(px.size()), px.data(), py.data());
          px.clear();
          py.clear();
        };
        for (std::size_t i = 0; i < s.x.size(); ++i) {
          if (std::isfinite(ys[k][i]) && std::isfinite(s.x[i])) {
            px.push_back(s.x[i]);
            py.push_back(ys[k][i]);
          } else {
            flush();
          }
        }
        flush();
      }
      opt[k] = s.markers ? PL_LEGEND_SYMBOL : PL_LEGEND_LINE;
      colours[k] = colour;
      texts[k] = s.name.c_str();
      symbols[k] = "#(728)";
    }
    PLFLT legend_width = 0, legend_height = 0;
    plcol0(1);
    pllegend(&legend_width, &legend_height, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX,
             PL_POSITION_RIGHT | PL_POSITION_TOP | PL_POSITION_INSIDE, 0.02, 0.02, 0.08, 0, 1, 1, 0,
             0, static_cast<PLINT>(plot.series.size()), opt.data(), 1.0, 0.9, 2.0, 0.0,
             colours.data(), texts.data(), nullptr, nullptr, nullptr, nullptr, colours.data(),
             styles.data(), widths.data(), colours.data(), symbol_scales.data(),
             symbol_numbers.data(), symbols.data());
    plend1();
    plsstrm(previous);
  }
  const std::unique_ptr<char, decltype(&std::free)> owned(image, &std::free);
  if (image_size == 0) throw std::runtime_error("plot: PLplot drew nothing for " + path.string());
  write_whole_file(output.temporary_path(), {image, image_size});
  output.commit();
}

}  // namespace scatterlab
