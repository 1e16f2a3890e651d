#pragma once
// PNG line plots for validation figures and reports: several named series (lines, or markers
// with error bars for Monte Carlo), a linear, logarithmic or square-root y axis (Bitterli §3.6.3:
// log for the far field, sqrt to see near-source errors), axis labels and a legend.
// Drawn by PLplot's pngcairo device (Debian: libplplot-dev, plplot-driver-cairo) and written
// atomically: a temporary file beside the target, renamed into place when complete.

#include <filesystem>
#include <string>
#include <vector>

namespace scatterlab {

enum class AxisScale { linear, log, sqrt };

struct PlotSeries {
  std::string name;                  // legend text
  std::vector<double> x, y;          // same length
  std::vector<double> y_error;       // empty, or one standard error per point (drawn as +-1)
  bool markers = false;              // points (with error bars) instead of a line
};

struct LinePlot {
  std::string title;
  std::string x_label;
  std::string y_label;
  AxisScale y_scale = AxisScale::linear;
  std::vector<PlotSeries> series;
  int width = 1000, height = 700;  // pixels
};

// Points that the scale cannot show (y <= 0 on a log axis, y < 0 on a sqrt axis, non-finite
// values) are left out, breaking the line there. Throws InputError ("plot") for a plot with no
// series, mismatched lengths or no drawable point, std::runtime_error when the pngcairo device
// is missing or the file cannot be written. Safe to call from several threads (serialised).
void write_png(const LinePlot& plot, const std::filesystem::path& path);

std::string to_string(AxisScale scale);

}  // namespace scatterlab
