#pragma once
// PNG line plots for validation figures and reports: several named series (lines, or markers
// with error bars for Monte Carlo), a linear, logarithmic or square-root y axis (Bitterli §3.6.3:
// log for the far field, sqrt to see near-source errors), axis labels and a legend; and titled
// images side by side (ImageFigure).
// Drawn by matplotlib (Debian: python3-matplotlib) in a python3 process that write_png starts:
// the plot goes to it as JSON, and the script that draws it (sim/io/plot_figure.py) is compiled
// into the library, so that the program finds it wherever it runs. Each series names its model
// (`model`), which fixes its colour, line style and marker in every figure; the exact reference
// is drawn on top. Written atomically: a temporary file beside the target, renamed into place
// when complete.

#include <filesystem>
#include <string>
#include <vector>

#include "scatterlab/io/image.hpp"

namespace scatterlab {

enum class AxisScale { linear, log, sqrt };

struct PlotSeries {
  std::string name;             // legend text, as the model's paper names it
  std::vector<double> x, y;     // same length
  std::vector<double> y_error;  // empty, or one standard error per point (drawn as +-1)
  bool markers = false;         // points (with error bars) instead of a line
  // The model's style key: the same colour, line style and marker in every figure. Known keys
  // (plot_figure.py): exact, single_scatter, monte_carlo, monte_carlo_all_orders, collision,
  // track_length, standard_error, diffusion, dipole, better_dipole, quantized_diffusion,
  // grosjean, grosjean_beam, measured, straight, walter, holzschuch, pathtrace, and
  // "<key>+single_scatter" (drawn as <key>). Empty or unknown: the next free colour.
  std::string model = {};
  // Empty, or a short text per point, drawn beside it (error against photons: each point's wall
  // time, which under load need not grow with the photons and so makes a poor axis).
  std::vector<std::string> point_labels = {};
};

struct LinePlot {
  std::string title;    // "\n" breaks a long title; matplotlib mathtext ($\sigma_a$) is drawn
  std::string x_label;  // with its unit, e.g. "r (mfp)"
  std::string y_label;  // with its unit
  AxisScale y_scale = AxisScale::linear;
  bool log_x = false;  // a logarithmic x axis (error against run time); linear otherwise
  std::vector<PlotSeries> series;
  int width = 1050, height = 600;  // pixels, at 150 dots per inch
};

struct PlotFile {
  LinePlot plot;
  std::filesystem::path path;
};

// Points that the scale cannot show (y <= 0 on a log axis, y < 0 on a sqrt axis, x <= 0 on a
// log x axis, non-finite values) are left out, breaking the line there. Throws InputError
// ("plot") for a plot with no series, mismatched lengths or no drawable point, before anything
// is written; std::runtime_error when python3 or matplotlib is missing ("figures need python3
// with matplotlib (Debian: python3-matplotlib)"), when drawing fails (python's message
// included) or when the file cannot be written. The python3 run is $SCATTERLAB_PYTHON when set,
// else /usr/bin/python3 when it exists, else python3 on the PATH. Safe to call from several
// threads: each call runs its own process in its own scratch directory.
void write_png(const LinePlot& plot, const std::filesystem::path& path);

// Several plots drawn by one python3 process (python and matplotlib start once, ~0.5 s): all
// are checked before any is drawn, and each file is written as write_png writes it.
void write_pngs(const std::vector<PlotFile>& plots);

// Images side by side, each with its title, all at one exposure (render --study: the reference
// and each method's image).
struct ImagePanel {
  std::string title;             // "\n" breaks it
  const Image* image = nullptr;  // every panel the same size
};

struct ImageFigure {
  std::string title;
  std::vector<ImagePanel> panels;
  double exposure = 0.0, gamma = 2.2;  // as write_png of an Image: (value * 2^exposure)^(1/gamma)
  int width = 1500, height = 420;      // pixels, at 150 dots per inch
};

// Written as write_png of a LinePlot is, with the same errors (InputError "plot" for no panel,
// a missing image or panels of different sizes; "gamma" and "exposure" as write_png of an Image).
void write_png(const ImageFigure& figure, const std::filesystem::path& path);

// Throws write_png's std::runtime_error ("figures need python3 with matplotlib ...") when python3
// or matplotlib is missing; commands that write figures call it before their work, so that a
// long run does not fail at its end. Starts python3 and imports matplotlib: about 0.3 s.
void require_plotting();

std::string to_string(AxisScale scale);

}  // namespace scatterlab
