#include "scatterlab/render/render_study.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/atomic_output.hpp"
#include "scatterlab/io/plot.hpp"

namespace scatterlab {

namespace {

constexpr RenderMethod study_methods[] = {RenderMethod::straight, RenderMethod::walter,
                                          RenderMethod::holzschuch, RenderMethod::pathtrace};

RenderResult render_at(RenderScene scene, RenderMethod method, int samples,
                       const RenderStudyOptions& options) {
  scene.samples = samples;
  RenderSettings settings;
  settings.method = method;
  settings.threads = options.threads;
  settings.seed = options.seed;
  return render_single_scatter(scene, settings);
}

// Mean z^2 of a Monte Carlo image against the reference, over the pixels with a standard error.
double mean_z2(const RenderResult& result, const Image& reference) {
  double sum = 0.0;
  int count = 0;
  for (std::size_t k = 0; k < reference.values.size(); ++k) {
    const double se = result.standard_error.values[k];
    if (!(se > 0.0)) continue;
    const double z = (result.image.values[k] - reference.values[k]) / se;
    sum += z * z;
    ++count;
  }
  return count > 0 ? sum / count : std::numeric_limits<double>::quiet_NaN();
}

// One exposure for every panel: the reference's 99th percentile maps to white.
double exposure_for(const Image& reference) {
  std::vector<double> values = reference.values;
  const auto k = static_cast<std::ptrdiff_t>(0.99 * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  const double high = values[static_cast<std::size_t>(k)];
  return high > 0.0 ? -std::log2(high) : 0.0;
}

void write_csv(const std::vector<RenderStudyRow>& rows, const std::filesystem::path& path) {
  write_text_file(path, [&rows](std::ostream& file) {
    file << "scene,method,budget,light_samples,seconds,rmse,relative_error,mean_z2\n";
    for (const RenderStudyRow& row : rows) {
      file << fmt::format("{},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g}\n", row.scene,
                          to_string(row.method), row.budget, row.light_samples, row.seconds,
                          row.rmse, row.relative_error, row.mean_z2);
    }
  });
}

// A method's name in a legend, with the paper it follows (render/single_scatter_renderer.hpp).
std::string method_name(RenderMethod method) {
  switch (method) {
    case RenderMethod::straight:
      return "straight shadow rays (Jensen et al. 2001)";
    case RenderMethod::walter:
      return "refracted paths (Walter et al. 2009)";
    case RenderMethod::holzschuch:
      return "support intervals (Holzschuch 2013)";
    case RenderMethod::pathtrace:
      return "path tracing (Monte Carlo)";
    case RenderMethod::volumetric:  // not in the study: it renders more than single scattering
      return "volumetric path tracing (every order)";
    case RenderMethod::bssrdf:  // not in the study either: multiple scattering only
      return "diffusion BSSRDF on a point cloud";
  }
  return to_string(method);
}

void write_error_plot(const std::string& scene, const std::vector<RenderStudyRow>& rows,
                      const std::filesystem::path& path) {
  LinePlot plot;
  plot.title = fmt::format("{}: once-scattered image, error against run time", scene);
  plot.x_label = "wall-clock time per image (s)";
  plot.y_label = "relative RMS error against the reference image";
  plot.y_scale = AxisScale::log;
  plot.log_x = true;
  for (const RenderMethod method : study_methods) {
    PlotSeries series;
    series.name = method_name(method);
    series.model = to_string(method);
    for (const RenderStudyRow& row : rows) {
      if (row.scene != scene || row.method != method) continue;
      // A log axis cannot show 0 s; the clock's resolution is the floor.
      series.x.push_back(std::max(row.seconds, 1e-6));
      series.y.push_back(row.relative_error);
    }
    if (!series.x.empty()) plot.series.push_back(std::move(series));
  }
  write_png(plot, path);
}

}  // namespace

RenderStudyOptions RenderStudyOptions::quick() {
  RenderStudyOptions options;
  options.size = 8;
  options.budgets = {1, 4};
  options.pathtrace_budgets = {2000, 8000};
  options.reference_samples = 8;
  options.reference_light_samples = 4;
  return options;
}

void image_errors(const Image& image, const Image& reference, double& rmse,
                  double& relative_error) {
  if (image.width != reference.width || image.height != reference.height) {
    throw std::invalid_argument("image_errors: images of different sizes");
  }
  double squared = 0.0, reference_squared = 0.0;
  for (std::size_t k = 0; k < image.values.size(); ++k) {
    const double d = image.values[k] - reference.values[k];
    squared += d * d;
    reference_squared += reference.values[k] * reference.values[k];
  }
  rmse = std::sqrt(squared / static_cast<double>(std::max<std::size_t>(image.values.size(), 1)));
  relative_error = reference_squared > 0.0 ? std::sqrt(squared / reference_squared)
                                           : std::numeric_limits<double>::infinity();
}

std::vector<RenderStudyRow> run_render_study(
    const std::vector<RenderStudyScene>& scenes, const RenderStudyOptions& options,
    const std::filesystem::path& out_dir,
    const std::function<void(const RenderStudyRow&)>& on_row) {
  if (options.size < 1 || options.budgets.empty() || options.pathtrace_budgets.empty() ||
      options.reference_samples < 1) {
    throw InputError("study", "an empty study", "size, budgets and samples >= 1");
  }
  // Fail before the work: the directory must exist (InputError "out").
  { const AtomicOutput check(out_dir / "render_study.csv"); }

  std::vector<RenderStudyRow> rows;
  for (const RenderStudyScene& entry : scenes) {
    RenderScene scene = entry.scene;
    scene.width = scene.height = options.size;
    RenderScene reference_scene = scene;
    reference_scene.light_samples = options.reference_light_samples;
    const RenderResult reference =
        render_at(reference_scene, RenderMethod::holzschuch, options.reference_samples, options);
    std::vector<RenderResult> largest;
    for (const RenderMethod method : study_methods) {
      RenderResult last;
      const bool pathtrace = method == RenderMethod::pathtrace;
      for (const int samples : pathtrace ? options.pathtrace_budgets : options.budgets) {
        // A deterministic budget is both the points per ray and the points on the light.
        if (!pathtrace) scene.light_samples = samples;
        RenderResult result = render_at(scene, method, samples, options);
        RenderStudyRow row;
        row.scene = entry.name;
        row.method = method;
        row.budget = samples;
        row.light_samples = pathtrace ? 0 : scene.light_samples;
        row.seconds = result.seconds;
        image_errors(result.image, reference.image, row.rmse, row.relative_error);
        if (pathtrace) row.mean_z2 = mean_z2(result, reference.image);
        rows.push_back(row);
        if (on_row) on_row(row);
        last = std::move(result);
      }
      largest.push_back(std::move(last));
    }
    write_error_plot(entry.name, rows, out_dir / (entry.name + "_error.png"));
    // The reference and each method at its largest budget, titled, at one exposure.
    ImageFigure figure;
    figure.title =
        fmt::format("{}: once-scattered radiance, {} x {} pixels, one exposure for every image",
                    entry.name, options.size, options.size);
    figure.exposure = exposure_for(reference.image);
    figure.panels.push_back(
        {fmt::format("reference: {}\n{} points per interval, {} on the light",
                     method_name(RenderMethod::holzschuch), options.reference_samples,
                     options.reference_light_samples),
         &reference.image});
    for (std::size_t m = 0; m < largest.size(); ++m) {
      const RenderMethod method = study_methods[m];
      const std::string budget =
          method == RenderMethod::pathtrace
              ? fmt::format("{} paths per pixel", options.pathtrace_budgets.back())
              : fmt::format("{} points per ray and on the light", options.budgets.back());
      figure.panels.push_back(
          {fmt::format("{}\n{}", method_name(method), budget), &largest[m].image});
    }
    write_png(figure, out_dir / (entry.name + "_images.png"));
  }
  write_csv(rows, out_dir / "render_study.csv");
  return rows;
}

}  // namespace scatterlab
