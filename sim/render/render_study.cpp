#include "scatterlab/render/render_study.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
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
                       const RenderStudyOptions& options, const WorkProgress& progress) {
  scene.samples = samples;
  RenderSettings settings;
  settings.method = method;
  settings.threads = options.threads;
  settings.seed = options.seed;
  return render_single_scatter(scene, settings, progress);
}

// Mean z^2 of a Monte Carlo image against the (Monte Carlo) reference, over the pixels with a
// standard error: the two are independent, so their variances add.
double mean_z2(const RenderResult& result, const RenderResult& reference) {
  double sum = 0.0;
  int count = 0;
  for (std::size_t k = 0; k < reference.image.values.size(); ++k) {
    const double se = result.standard_error.values[k];
    if (!(se > 0.0)) continue;
    const double se_ref = reference.standard_error.values[k];
    const double z =
        (result.image.values[k] - reference.image.values[k]) / std::sqrt(se * se + se_ref * se_ref);
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
    file << "scene,method,budget,light_samples,seconds,rmse,relative_error,mean_z2,"
            "reference_noise,resolution\n";
    for (const RenderStudyRow& row : rows) {
      file << fmt::format("{},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}\n", row.scene,
                          to_string(row.method), row.budget, row.light_samples, row.seconds,
                          row.rmse, row.relative_error, row.mean_z2, row.reference_noise,
                          row.resolution);
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
  plot.y_label = "relative RMS error against the path-traced reference";
  plot.y_scale = AxisScale::log;
  plot.log_x = true;
  double resolution = 0.0, fastest = std::numeric_limits<double>::infinity(), slowest = 0.0;
  for (const RenderMethod method : study_methods) {
    PlotSeries series;
    series.name = method_name(method);
    series.model = to_string(method);
    for (const RenderStudyRow& row : rows) {
      if (row.scene != scene || row.method != method) continue;
      // A log axis cannot show 0 s; the clock's resolution is the floor.
      series.x.push_back(std::max(row.seconds, 1e-6));
      // An error the reference does not resolve is drawn on the line of its resolution.
      series.y.push_back(std::max(row.relative_error, row.resolution));
      resolution = row.resolution;
      fastest = std::min(fastest, series.x.back());
      slowest = std::max(slowest, series.x.back());
    }
    if (!series.x.empty()) plot.series.push_back(std::move(series));
  }
  if (slowest > 0.0) {
    PlotSeries floor;
    floor.name = "the reference's resolution (its noise subtracted): errors on it are at most it";
    floor.model = "resolution";
    floor.x = {fastest, slowest};
    floor.y = {resolution, resolution};
    plot.series.push_back(std::move(floor));
  }
  write_png(plot, path);
}

}  // namespace

RenderStudyOptions RenderStudyOptions::quick() {
  RenderStudyOptions options;
  // 32 x 32: the smallest image in which a reader sees the object; budgets small to match.
  options.size = 32;
  options.budgets = {1, 2};
  options.pathtrace_budgets = {1000, 4000};
  options.reference_samples = 16000;
  return options;
}

ImageErrors image_errors(const Image& image, const Image& reference, const Image& reference_error) {
  if (image.width != reference.width || image.height != reference.height ||
      reference_error.width != reference.width || reference_error.height != reference.height) {
    throw std::invalid_argument("image_errors: images of different sizes");
  }
  double squared = 0.0, reference_squared = 0.0, noise = 0.0, noise_squared = 0.0;
  for (std::size_t k = 0; k < image.values.size(); ++k) {
    const double d = image.values[k] - reference.values[k];
    const double variance = reference_error.values[k] * reference_error.values[k];
    squared += d * d;
    reference_squared += reference.values[k] * reference.values[k];
    noise += variance;
    noise_squared += variance * variance;
  }
  const double excess = std::max(0.0, squared - noise);
  const double norm2 = reference_squared - noise;
  const double infinity = std::numeric_limits<double>::infinity();
  ImageErrors errors;
  errors.rmse =
      std::sqrt(excess / static_cast<double>(std::max<std::size_t>(image.values.size(), 1)));
  errors.relative_error = norm2 > 0.0 ? std::sqrt(excess / norm2) : infinity;
  errors.reference_noise = norm2 > 0.0 ? std::sqrt(noise / norm2) : infinity;
  errors.resolution = norm2 > 0.0 ? std::sqrt(std::sqrt(2.0 * noise_squared) / norm2) : infinity;
  return errors;
}

RenderStudyResult run_render_study(const std::vector<RenderStudyScene>& scenes,
                                   const RenderStudyOptions& options,
                                   const std::filesystem::path& out_dir,
                                   const std::function<void(const RenderStudyRow&)>& on_row,
                                   const StudyProgress& progress) {
  if (options.size < 1 || options.budgets.empty() || options.pathtrace_budgets.empty() ||
      options.reference_samples < 2) {
    throw InputError("study", "an empty study",
                     "size and budgets >= 1, and at least 2 samples for the reference");
  }
  // Fail before the work: the directory must exist (InputError "out").
  { const AtomicOutput check(out_dir / "render_study.csv"); }

  const std::size_t runs =
      scenes.size() * (1 + (std::size(study_methods) - 1) * options.budgets.size() +
                       options.pathtrace_budgets.size());
  std::size_t run = 0;
  const auto progress_of = [&](const std::string& scene, const std::string& what) {
    ++run;
    return progress ? progress(fmt::format("{}: run {} of {}, {}", scene, run, runs, what))
                    : WorkProgress{};
  };
  std::vector<RenderStudyRow> rows;
  std::vector<std::filesystem::path> written;
  for (const RenderStudyScene& entry : scenes) {
    RenderScene scene = entry.scene;
    scene.width = scene.height = options.size;
    // A seed of its own: the ranked pathtrace runs must not share the reference's samples.
    RenderStudyOptions reference_options = options;
    reference_options.seed = options.seed + 1;
    const RenderResult reference =
        render_at(scene, RenderMethod::pathtrace, options.reference_samples, reference_options,
                  progress_of(entry.name, fmt::format("the reference, pathtrace at {} samples",
                                                      options.reference_samples)));
    std::vector<RenderResult> largest;
    for (const RenderMethod method : study_methods) {
      RenderResult last;
      const bool pathtrace = method == RenderMethod::pathtrace;
      for (const int samples : pathtrace ? options.pathtrace_budgets : options.budgets) {
        // A deterministic budget is both the points per ray and the points on the light.
        if (!pathtrace) scene.light_samples = samples;
        RenderResult result = render_at(
            scene, method, samples, options,
            progress_of(entry.name, fmt::format("{} at {} samples", to_string(method), samples)));
        RenderStudyRow row;
        row.scene = entry.name;
        row.method = method;
        row.budget = samples;
        row.light_samples = pathtrace ? 0 : scene.light_samples;
        row.seconds = result.seconds;
        const ImageErrors errors =
            image_errors(result.image, reference.image, reference.standard_error);
        row.rmse = errors.rmse;
        row.relative_error = errors.relative_error;
        row.reference_noise = errors.reference_noise;
        row.resolution = errors.resolution;
        if (pathtrace) row.mean_z2 = mean_z2(result, reference);
        rows.push_back(row);
        if (on_row) on_row(row);
        last = std::move(result);
      }
      largest.push_back(std::move(last));
    }
    written.push_back(out_dir / (entry.name + "_error.png"));
    write_error_plot(entry.name, rows, written.back());
    // The reference and each method at its largest budget, titled, at one exposure.
    ImageFigure figure;
    figure.title =
        fmt::format("{}: once-scattered radiance, {} x {} pixels, one exposure for every image",
                    entry.name, options.size, options.size);
    figure.exposure = exposure_for(reference.image);
    figure.panels.push_back(
        {fmt::format("reference: {}\n{} paths per pixel, noise {:.2g} %",
                     method_name(RenderMethod::pathtrace), options.reference_samples,
                     100.0 * rows.back().reference_noise),
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
    written.push_back(out_dir / (entry.name + "_images.png"));
    write_png(figure, written.back());
  }
  written.push_back(out_dir / "render_study.csv");
  write_csv(rows, written.back());
  return {std::move(rows), std::move(written)};
}

}  // namespace scatterlab
