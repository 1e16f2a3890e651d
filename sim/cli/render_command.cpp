#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "commands.hpp"
#include "log_interval_option.hpp"
#include "memory_limit_option.hpp"
#include "prepare_outputs.hpp"
#include "progress_reporter.hpp"
#include "run_options.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/io/atomic_output.hpp"
#include "scatterlab/io/plot.hpp"
#include "scatterlab/models/diffusion_profile.hpp"
#include "scatterlab/render/bssrdf_renderer.hpp"
#include "scatterlab/render/exposure.hpp"
#include "scatterlab/render/render_scene.hpp"
#include "scatterlab/render/render_study.hpp"
#include "scatterlab/render/single_scatter_renderer.hpp"
#include "scatterlab/render/volumetric_renderer.hpp"
#include "shipped_path.hpp"

namespace scatterlab::cli {

namespace {

struct RenderOptions {
  std::vector<std::string> scenes;
  bool study = false, quick = false;
  std::string method = "holzschuch";
  int width = 0, height = 0, samples = 0, light_samples = 0, threads = 0;
  std::uint64_t seed = 1;
  std::string out = "render.exr";
  double exposure = 0.0;
  double gamma = 2.2;
  // --method bssrdf
  std::string model = "better_dipole";
  int points = BssrdfSettings{}.cloud.points;
  int relaxation = BssrdfSettings{}.cloud.relaxation;
  double cluster_angle = BssrdfSettings{}.cluster_angle;
  bool no_occlusion = false;
};

// The flags of method bssrdf alone.
constexpr const char* bssrdf_flags[] = {"--model", "--points", "--relaxation", "--cluster-angle",
                                        "--no-occlusion"};

// `render --method bssrdf`: the point cloud, its octree and the image, and the per-point file.
int run_bssrdf(const RenderOptions& o, const RenderScene& scene, const std::filesystem::path& exr,
               const std::filesystem::path& png, bool auto_exposed, double log_interval) {
  BssrdfSettings settings;
  settings.model = parse_profile_model(o.model, "--model");
  for (const auto& [flag, value, lowest, highest] :
       {std::tuple{"--points", o.points, 1, max_cloud_points},
        std::tuple{"--relaxation", o.relaxation, 0, max_relaxation}}) {
    if (value < lowest || value > highest) {
      throw InputError(flag, fmt::format("got {}", value),
                       fmt::format("an integer in [{}, {}]", lowest, highest));
    }
  }
  if (!(o.cluster_angle >= 0.0) || !std::isfinite(o.cluster_angle)) {
    throw InputError("--cluster-angle", fmt::format("got {}", o.cluster_angle),
                     "a solid angle >= 0 in sr (0: every point summed, no clustering)");
  }
  settings.cloud.points = o.points;
  settings.cloud.relaxation = o.relaxation;
  settings.cloud.seed = o.seed;
  settings.cluster_angle = o.cluster_angle;
  settings.occlusion = !o.no_occlusion;
  settings.threads = o.threads;
  check_bssrdf_work(scene, settings, "--cluster-angle");
  std::filesystem::path h5 = exr;
  h5.replace_extension(".h5");

  OutputPlan plan;
  plan.input("SCENE", o.scenes.front());
  if (!scene.mesh_file.empty()) plan.input("mesh.path", scene.mesh_file);
  plan.output_file("--out", exr);
  plan.output_file("--out", png);
  plan.output_file("--out", h5);  // the per-point exitance beside the images
  prepare_outputs(plan);
  if (exr.extension() != ".exr") {
    throw InputError("--out", fmt::format("got '{}'", o.out),
                     "a file name ending in .exr (NAME.png and NAME.h5 are written beside it)");
  }
  { const AtomicOutput exr_check(exr), png_check(png), h5_check(h5); }

  ProgressReporter reporter("render bssrdf", "steps (relaxation, then tiles)", log_interval);
  const WorkProgress progress = [&reporter](std::uint64_t done, std::uint64_t tiles) {
    reporter.update(done, tiles);
  };
  const BssrdfResult result = render_bssrdf(scene, settings, progress);
  reporter.finish();
  const double exposure = auto_exposed ? auto_exposure(result.image) : o.exposure;
  write_exr(result.image, exr);
  write_png(result.image, png, exposure, o.gamma);
  write_point_cloud_file(h5, scene, settings, result);
  const BssrdfCounters& c = result.counters;
  // The power leaving over the power entering, per channel: what the half-space profile keeps
  // on this object (on a small object of little absorption, much less than R_dr: light the
  // profile sends past the object's size is lost).
  std::string kept;
  double entering = 0.0;
  for (const double e : result.irradiance) entering += e * result.cloud.point_area;
  for (int ch = 0; ch < result.channels; ++ch) {
    double leaving = 0.0;
    for (std::size_t i = 0; i < result.cloud.size(); ++i) {
      leaving += result.exitance[i * result.channels + ch] * result.cloud.point_area;
    }
    kept += fmt::format("{}{:.4f}", ch > 0 ? ", " : "", entering > 0.0 ? leaving / entering : 0.0);
  }
  fmt::print(
      "bssrdf {}: {}x{}, {} channel(s), {} points ({} relaxation iterations, {} lit), cluster "
      "angle {} sr, occlusion {}; octree {} nodes, depth {}\n"
      "seconds: point cloud {:.3f}, irradiance {:.3f}, octree {:.3f}, point exitance {:.3f}, "
      "image {:.3f}; {} eye rays, {:.1f} evaluations per pixel ({} clusters), {:.3g} "
      "evaluations/s; power leaving / entering {}; PNG exposure {:.2f} stops{}\nwrote {}, {} "
      "and {}\n",
      to_string(settings.model), scene.width, scene.height, result.channels, result.cloud.size(),
      settings.cloud.relaxation, c.lit_points, settings.cluster_angle,
      settings.occlusion ? "on" : "off", result.octree_nodes, result.octree_depth,
      result.seconds_cloud, result.seconds_irradiance, result.seconds_octree, result.seconds_points,
      result.seconds_image, c.eye_rays,
      static_cast<double>(c.evaluations) /
          static_cast<double>(std::max<std::uint64_t>(c.eye_rays, 1)),
      c.clusters, static_cast<double>(c.evaluations) / std::max(result.seconds_image, 1e-9), kept,
      exposure, auto_exposed ? " (auto)" : "", exr.string(), png.string(), h5.string());
  return 0;
}

// `render --study`: the study itself lives in sim/render/render_study.cpp.
int run_study(const RenderOptions& o, const std::filesystem::path& out_dir, double log_interval) {
  check_threads(o.threads, "--threads");
  check_seed(o.seed, "--seed");
  // The shipped scenes by default, found from any directory.
  std::vector<std::string> paths = o.scenes;
  if (paths.empty()) {
    for (const char* name : {"bumpy-sphere.toml", "tile.toml"}) {
      paths.push_back(shipped_path(std::filesystem::path("scenes") / name,
                                   std::filesystem::path(SCATTERLAB_SOURCE_DATA) / "scenes" / name)
                          .string());
    }
  }
  OutputPlan plan;
  for (const std::string& path : paths) plan.input("SCENE", path);
  plan.output_directory("--out", out_dir);
  prepare_outputs(plan);
  std::vector<RenderStudyScene> scenes;
  for (const std::string& path : paths) {
    scenes.push_back({std::filesystem::path(path).stem().string(), load_render_scene(path)});
  }
  require_plotting();  // before the renders, not after them
  plan.make_output_directories();
  RenderStudyOptions options = o.quick ? RenderStudyOptions::quick() : RenderStudyOptions{};
  options.threads = o.threads;
  options.seed = o.seed;
  fmt::print("study: {}x{} pixels, reference path-traced at {} samples per pixel (its own seed)\n",
             options.size, options.size, options.reference_samples);
  // One bar (with its ETA) per render, cleared before the render's line is printed.
  std::unique_ptr<ProgressReporter> reporter;
  const StudyProgress progress = [&reporter, log_interval](const std::string& what) {
    reporter = std::make_unique<ProgressReporter>("study " + what, "tiles", log_interval);
    return WorkProgress(
        [&reporter](std::uint64_t done, std::uint64_t tiles) { reporter->update(done, tiles); });
  };
  const auto on_row = [&reporter](const RenderStudyRow& row) {
    if (reporter) reporter->finish();
    fmt::print("{:>14} {:>10} budget {:>6}: {:9.3f} s, rmse {:.4g}, relative error {:.4g}{}\n",
               row.scene, to_string(row.method), row.budget, row.seconds, row.rmse,
               row.relative_error,
               std::isnan(row.mean_z2) ? "" : fmt::format(", mean z^2 {:.3g}", row.mean_z2));
    std::fflush(stdout);
  };
  const RenderStudyResult study = run_render_study(scenes, options, out_dir, on_row, progress);
  reporter.reset();
  for (const std::filesystem::path& path : study.written) fmt::print("wrote {}\n", path.string());
  return 0;
}

}  // namespace

Action add_render_command(CLI::App& app) {
  auto* render = app.add_subcommand(
      "render",
      "Image of a refractive mesh, single scattering or (volumetric) all of the light transport "
      "(OpenEXR, linear, and a PNG beside it)");
  auto options = std::make_shared<RenderOptions>();
  render
      ->add_option("SCENE,--scene", options->scenes,
                   "Render scene (TOML; see data/scenes/tile.toml); with --study, the scenes "
                   "to study (by default data/scenes/bumpy-sphere.toml and "
                   "data/scenes/tile.toml)")
      ->default_str("");
  render->add_flag("--study", options->study,
                   "Error against run time: every method at increasing budgets against a "
                   "path-traced reference (2^20 samples per pixel, its noise subtracted); writes "
                   "render_study.csv, <scene>_error.png and <scene>_images.png into --out (a "
                   "directory); not with --method, --width, --height, --samples, "
                   "--light-samples, --exposure, --gamma");
  render->add_flag("--quick", options->quick, "With --study: tiny images and budgets");
  render->add_option("--method", options->method,
                     "straight (Jensen 2001), walter (sample points), holzschuch (support "
                     "intervals), pathtrace (Monte Carlo reference, needs light.radius > 0), "
                     "volumetric (volumetric path tracing of every order, the floor and "
                     "colour; needs light.radius > 0), or bssrdf (multiple scattering of a "
                     "diffusion BSSRDF on a point cloud; writes NAME.h5 of the per-point "
                     "exitance too)");
  render->add_option("--model", options->model,
                     "With --method bssrdf: the diffusion profile, dipole, better_dipole or "
                     "quantized_diffusion");
  render->add_option("--points", options->points,
                     "With --method bssrdf: points on the mesh, in [1, 2^22]");
  render->add_option("--relaxation", options->relaxation,
                     "With --method bssrdf: point repulsion iterations (Turk), in [0, 100000]");
  render->add_option("--cluster-angle", options->cluster_angle,
                     "With --method bssrdf: octree nodes subtending less than this solid angle "
                     "(sr) are evaluated as one point; 0 sums every point");
  render->add_flag("--no-occlusion", options->no_occlusion,
                   "With --method bssrdf: no shadow rays (every point sees the light)");
  // These default to the scene's values, which --help cannot know.
  render->add_option("--width", options->width, "Image width in pixels, in [1, 16384]")
      ->default_str("the scene's");
  render->add_option("--height", options->height, "Image height in pixels, in [1, 16384]")
      ->default_str("the scene's");
  render
      ->add_option("--samples", options->samples,
                   "Samples per eye ray, per interval for holzschuch, paths per pixel for "
                   "volumetric, in [1, 2^20]")
      ->default_str("the scene's");
  render
      ->add_option("--light-samples", options->light_samples,
                   "Points on a sphere light for the deterministic methods, in [1, 4096]")
      ->default_str("the scene's");
  render->add_option("--threads", options->threads, threads_help());
  add_memory_limit_option(*render);
  render->add_option("--seed", options->seed,
                     "Random seed (pathtrace, volumetric), in [0, 2^63 - 1]");
  CLI::Option* out_option = render->add_option(
      "-o,--out", options->out,
      "Output OpenEXR file, NAME.exr; the PNG is written beside it as NAME.png "
      "(--study: the output directory, new, empty or one scatterlab wrote, made if "
      "missing; by default render-study)");
  CLI::Option* exposure_option =
      render->add_option("--exposure", options->exposure, "PNG exposure in stops")
          ->default_str("auto: the 99th percentile of the lit pixels maps to white");
  render->add_option("--gamma", options->gamma, "PNG gamma");
  const auto log_interval = add_log_interval_option(*render);
  // The study chooses its own methods, sizes, budgets and plots: these would be ignored.
  CLI::Option* study = render->get_option("--study");
  for (const char* flag : {"--method", "--width", "--height", "--samples", "--light-samples",
                           "--exposure", "--gamma"}) {
    study->excludes(render->get_option(flag));
  }
  for (const char* flag : bssrdf_flags) study->excludes(render->get_option(flag));
  return [options, out_option, exposure_option, render, log_interval] {
    const RenderOptions& o = *options;
    if (o.study) {
      return run_study(o, out_option->count() > 0 ? o.out : "render-study", *log_interval);
    }
    if (o.quick) throw InputError("quick", "given without --study", "--quick with --study");
    if (o.method != "bssrdf") {
      for (const char* flag : bssrdf_flags) {
        if (render->get_option(flag)->count() > 0) {
          throw InputError(flag, "given without --method bssrdf",
                           std::string(flag) + " with --method bssrdf");
        }
      }
    }
    if (o.scenes.size() != 1) {
      throw InputError("SCENE", fmt::format("{} scene files", o.scenes.size()),
                       "exactly one scene file (several only with --study)");
    }
    RenderSettings settings;
    settings.method = parse_render_method(o.method);
    RenderScene scene = load_render_scene(o.scenes.front());
    // A flag given overrides the scene's value, held to the same range (render_scene.hpp).
    for (const auto& [flag, value, highest, target] :
         {std::tuple{"--width", o.width, max_image_side, &scene.width},
          std::tuple{"--height", o.height, max_image_side, &scene.height},
          std::tuple{"--samples", o.samples, max_samples, &scene.samples},
          std::tuple{"--light-samples", o.light_samples, max_light_samples,
                     &scene.light_samples}}) {
      if (render->get_option(flag)->count() == 0) continue;
      if (value < 1 || value > highest) {
        throw InputError(flag, fmt::format("got {}", value),
                         fmt::format("an integer in [1, {}]", highest));
      }
      *target = value;
    }
    check_threads(o.threads, "--threads");
    check_seed(o.seed, "--seed");
    if (!(o.gamma > 0.0)) throw InputError("gamma", fmt::format("got {}", o.gamma), "a number > 0");
    settings.threads = o.threads;
    settings.seed = o.seed;
    const std::filesystem::path exr(o.out);
    std::filesystem::path png = exr;
    png.replace_extension(".png");
    if (png == exr) png += ".png";
    const bool auto_exposed = exposure_option->count() == 0;
    if (settings.method == RenderMethod::bssrdf) {
      check_render_memory(scene, settings);  // the image
      return run_bssrdf(o, scene, exr, png, auto_exposed, *log_interval);
    }
    check_render_work(scene, settings);
    check_render_memory(scene, settings);

    // Fail before the work, not after it.
    OutputPlan plan;
    plan.input("SCENE", o.scenes.front());
    if (!scene.mesh_file.empty()) plan.input("mesh.path", scene.mesh_file);
    plan.output_file("--out", exr);
    plan.output_file("--out", png);  // the PNG beside the OpenEXR file
    prepare_outputs(plan);
    // The image is written as OpenEXR under --out and as PNG beside it: a name that says another
    // format would hold the wrong bytes.
    if (exr.extension() != ".exr") {
      throw InputError("--out", fmt::format("got '{}'", o.out),
                       "a file name ending in .exr (the PNG is written beside it, as NAME.png)");
    }
    { const AtomicOutput exr_check(exr), png_check(png); }

    ProgressReporter reporter("render " + o.method, "tiles", *log_interval);
    const WorkProgress progress = [&reporter](std::uint64_t done, std::uint64_t tiles) {
      reporter.update(done, tiles);
    };
    if (settings.method == RenderMethod::volumetric) {
      const VolumetricResult result = render_volumetric(scene, settings, progress);
      reporter.finish();
      const double exposure = auto_exposed ? auto_exposure(result.image) : o.exposure;
      write_exr(result.image, exr);
      write_png(result.image, png, exposure, o.gamma);
      const VolumetricCounters& c = result.counters;
      fmt::print(
          "volumetric: {}x{}, {} paths per pixel, {:.3f} s, {} paths ({:.3g} "
          "paths/s), {} collisions, {} boundary events, {} light hits, {} shadow rays, {} lost; "
          "PNG exposure {:.2f} stops{}\nwrote {} and {}\n",
          scene.width, scene.height, scene.samples, result.seconds, c.paths,
          static_cast<double>(c.paths) / std::max(result.seconds, 1e-9), c.collisions, c.boundary,
          c.light_hits, c.shadow_rays, c.lost, exposure, auto_exposed ? " (auto)" : "",
          exr.string(), png.string());
      return 0;
    }
    const RenderResult result = render_single_scatter(scene, settings, progress);
    reporter.finish();
    const double exposure = auto_exposed ? auto_exposure(result.image) : o.exposure;
    write_exr(result.image, exr);
    write_png(result.image, png, exposure, o.gamma);
    double total = 0.0, peak = 0.0;
    for (const double v : result.image.values) {
      total += v;
      peak = std::max(peak, v);
    }
    fmt::print(
        "{}: {}x{}, {} samples/ray, {:.3f} s, {} eye rays, {} queries, {} paths ({} blocked), "
        "mean radiance {:.6g}, peak {:.6g}; PNG exposure {:.2f} stops{}\nwrote {} and {}\n",
        o.method, scene.width, scene.height, scene.samples, result.seconds,
        result.counters.eye_rays, result.counters.point_queries, result.counters.paths,
        result.counters.blocked_paths, total / static_cast<double>(result.image.values.size()),
        peak, exposure, auto_exposed ? " (auto)" : "", exr.string(), png.string());
    return 0;
  };
}

}  // namespace scatterlab::cli
