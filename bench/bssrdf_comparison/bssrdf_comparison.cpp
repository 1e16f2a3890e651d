// The diffusion BSSRDF on a point cloud (render --method bssrdf) against volumetric path tracing
// (render --method volumetric) of the same scene, and the point cloud's own error against run
// time: a measurement, not a test.
//
//   scatterlab_bssrdf_comparison SCENE OUT_DIR [--samples N] [--threads T] [--points N]
//                                [--no-sweep] [--quick]
//
// Like with like: the point cloud renders multiple scattering only (no single scattering, no
// light reflected off the surface), so the reference is the volumetric image of every order
// minus that of scattering order 1 (two independent runs), and the pixels whose mirror direction
// meets the light (its reflection off the surface, unscattered light the subtraction keeps) are
// left out. What remains in the reference and not in the model is the error of the model itself:
// the half-space diffusion profile applied on a curved surface, the discrete point cloud, and
// light that leaves the object and re-enters it (none: a convex object). The scene should have no
// floor (the point cloud refuses one).
//
// Writes OUT_DIR/bssrdf_comparison.h5 (images per channel: the reference's orders and
// standard errors, each model's image, the mask; the sweep as a table) and
// OUT_DIR/bssrdf_sweep.csv; bench/bssrdf_comparison/plot_comparison.py draws the figures.
//
// Sweep (better dipole): points x cluster angle, each image's second-pass seconds against its
// relative error to (a) the converged point cloud (the most points, no clustering) and (b) the
// reference. Clustered against unclustered at equal error is Bitterli's Fig. 2.9.

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "scatterlab/io/hdf5_file.hpp"
#include "scatterlab/io/image.hpp"
#include "scatterlab/render/bssrdf_renderer.hpp"
#include "scatterlab/mesh/mesh_ray_tracer.hpp"
#include "scatterlab/render/render_scene.hpp"
#include "scatterlab/render/single_scatter_renderer.hpp"
#include "scatterlab/render/volumetric_renderer.hpp"

namespace {

using namespace scatterlab;

// Pixels seen on the mesh whose mirror reflection does not reach the light sphere.
std::vector<char> comparison_mask(const RenderScene& scene) {
  const MeshRayTracer tracer(scene.mesh);
  std::vector<char> mask(static_cast<std::size_t>(scene.width) * scene.height, 0);
  for (int j = 0; j < scene.height; ++j) {
    for (int i = 0; i < scene.width; ++i) {
      const Vec3 d = scene.camera.ray_direction(i, j, scene.width, scene.height);
      MeshHit hit;
      if (!tracer.intersect(scene.camera.position, d, 0.0, 1e300, hit)) continue;
      const auto t = hit.triangle;
      const double a = hit.bary_a, b = hit.bary_b;
      const Vec3 x = (1 - a - b) * scene.mesh.vertex(t, 0) + a * scene.mesh.vertex(t, 1) +
                     b * scene.mesh.vertex(t, 2);
      const Vec3 n = ((1 - a - b) * scene.mesh.corner_normal(t, 0) +
                      a * scene.mesh.corner_normal(t, 1) + b * scene.mesh.corner_normal(t, 2))
                         .normalized();
      const Vec3 r = d - 2.0 * d.dot(n) * n;
      const Vec3 oc = x - scene.light.position;
      const double bb = oc.dot(r);
      // 1.5 light radii: the shading normal's interpolation spreads the highlight a little.
      const double rad = 1.5 * scene.light.radius;
      const bool highlight = bb < 0.0 && bb * bb - (oc.squaredNorm() - rad * rad) >= 0.0;
      mask[static_cast<std::size_t>(j) * scene.width + i] = highlight ? 0 : 1;
    }
  }
  return mask;
}

struct ErrorStats {
  double median = 0.0, p90 = 0.0, mean_signed = 0.0;
};

// |a / b - 1| over every channel where b > 0, on the images averaged over blocks of block x block
// pixels that lie wholly in the mask (block 1: pixel by pixel; larger blocks average the
// reference's noise down).
ErrorStats relative_error(const RgbImage& a, const RgbImage& b, const std::vector<char>& mask,
                          int channels, int block = 1, int first = 0) {
  std::vector<double> e;
  double signed_sum = 0.0;
  const int w = a.width(), h = a.height();
  for (int c = first; c < channels; ++c) {
    for (int j0 = 0; j0 + block <= h; j0 += block) {
      for (int i0 = 0; i0 + block <= w; i0 += block) {
        double sa = 0.0, sb = 0.0;
        bool inside = true;
        for (int j = j0; j < j0 + block; ++j) {
          for (int i = i0; i < i0 + block; ++i) {
            inside = inside && mask[static_cast<std::size_t>(j) * w + i];
            sa += a.channels[c].at(i, j);
            sb += b.channels[c].at(i, j);
          }
        }
        if (!inside || !(sb > 0.0)) continue;
        const double rel = sa / sb - 1.0;
        e.push_back(std::abs(rel));
        signed_sum += rel;
      }
    }
  }
  ErrorStats s;
  if (e.empty()) return s;
  std::sort(e.begin(), e.end());
  s.median = e[e.size() / 2];
  s.p90 = e[static_cast<std::size_t>(0.9 * static_cast<double>(e.size() - 1))];
  s.mean_signed = signed_sum / static_cast<double>(e.size());
  return s;
}

std::vector<double> flatten(const RgbImage& image) {
  std::vector<double> v;
  for (const Image& c : image.channels) v.insert(v.end(), c.values.begin(), c.values.end());
  return v;
}

void write_image(hdf5::Group& group, const std::string& name, const RgbImage& image,
                 const std::string& units) {
  auto dataset = group.write_dataset(
      name, flatten(image),
      {3, static_cast<std::size_t>(image.height()), static_cast<std::size_t>(image.width())});
  dataset.write_string_attribute("units", units);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: %s SCENE OUT_DIR [--samples N] [--threads T] [--points N] [--no-sweep] "
                 "[--quick]\n",
                 argv[0]);
    return 2;
  }
  const std::filesystem::path scene_path = argv[1], out = argv[2];
  int samples = 0, threads = 0, points = 0;
  bool sweep_runs = true;
  bool quick = false;
  for (int k = 3; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "--samples" && k + 1 < argc)
      samples = std::stoi(argv[++k]);
    else if (a == "--threads" && k + 1 < argc)
      threads = std::stoi(argv[++k]);
    else if (a == "--points" && k + 1 < argc)
      points = std::stoi(argv[++k]);
    else if (a == "--no-sweep")
      sweep_runs = false;
    else if (a == "--quick")
      quick = true;
    else {
      std::fprintf(stderr, "unknown argument %s\n", a.c_str());
      return 2;
    }
  }
  std::filesystem::create_directories(out);
  RenderScene scene = load_render_scene(scene_path);
  if (quick) {
    scene.width = scene.height = 24;
    scene.samples = 64;
  }
  if (samples > 0) scene.samples = samples;
  const std::string unit = scene.medium.length_unit;
  const std::string radiance_units = "W sr^-1 " + unit + "^-2";
  const std::vector<char> mask = comparison_mask(scene);

  // The reference: every order, and order 1 alone, with independent seeds.
  RenderSettings reference;
  reference.method = RenderMethod::volumetric;
  reference.threads = threads;
  reference.seed = 11;
  const VolumetricResult all = render_volumetric(scene, reference);
  reference.scattering_order = 1;
  reference.seed = 12;
  const VolumetricResult single = render_volumetric(scene, reference);
  RgbImage multiple(scene.width, scene.height), multiple_error(scene.width, scene.height);
  for (int c = 0; c < 3; ++c) {
    for (std::size_t k = 0; k < multiple.channels[c].values.size(); ++k) {
      multiple.channels[c].values[k] =
          all.image.channels[c].values[k] - single.image.channels[c].values[k];
      multiple_error.channels[c].values[k] = std::hypot(
          all.standard_error.channels[c].values[k], single.standard_error.channels[c].values[k]);
    }
  }
  // The reference's own noise, as a relative error of the same statistic.
  RgbImage noisy = multiple;
  for (int c = 0; c < 3; ++c) {
    for (std::size_t k = 0; k < noisy.channels[c].values.size(); ++k) {
      noisy.channels[c].values[k] += multiple_error.channels[c].values[k];
    }
  }
  const int channels = scene.channel_media.empty() ? 1 : 3;
  const ErrorStats noise = relative_error(noisy, multiple, mask, channels);
  const ErrorStats noise4 = relative_error(noisy, multiple, mask, channels, 4);
  std::size_t masked = 0;
  for (const char m : mask) masked += m;
  fmt::print(
      "reference: {}x{}, {} paths per pixel, every order {:.1f} s, order 1 {:.1f} s; {} pixels "
      "compared; its standard error relative to multiple scattering: median {:.3f}, 90th "
      "percentile {:.3f} (4 x 4 blocks of errors summed, a bound: {:.3f}, {:.3f}; independent "
      "pixels average to a quarter of the per-pixel figure)\n",
      scene.width, scene.height, scene.samples, all.seconds, single.seconds, masked, noise.median,
      noise.p90, noise4.median, noise4.p90);
  std::fflush(stdout);

  hdf5::File file = hdf5::File::create(out / "bssrdf_comparison.h5");
  {  // the groups close before the file
    hdf5::Group root = file.root().create_group("comparison");
    root.write_string_attribute("scene", scene_path.string());
    root.write_int64_attribute("samples", scene.samples);
    root.write_int64_attribute("channels", channels);
    root.write_double_attribute("reference_seconds_all", all.seconds);
    root.write_double_attribute("reference_seconds_single", single.seconds);
    {
      hdf5::Group ref = root.create_group("reference");
      write_image(ref, "every_order", all.image, radiance_units);
      write_image(ref, "single", single.image, radiance_units);
      write_image(ref, "multiple", multiple, radiance_units);
      write_image(ref, "multiple_standard_error", multiple_error, radiance_units);
      std::vector<double> m(mask.begin(), mask.end());
      ref.write_dataset(
          "mask", m,
          {static_cast<std::size_t>(scene.height), static_cast<std::size_t>(scene.width)});
    }

    // Each model at the default settings.
    {
      hdf5::Group models = root.create_group("models");
      for (const ProfileModel model : all_profile_models) {
        BssrdfSettings s;
        s.model = model;
        s.threads = threads;
        if (quick) s.cloud.points = 2048;
        if (points > 0) s.cloud.points = points;
        const BssrdfResult r = render_bssrdf(scene, s);
        const ErrorStats e = relative_error(r.image, multiple, mask, channels);
        const ErrorStats e4 = relative_error(r.image, multiple, mask, channels, 4);
        fmt::print(
            "{:>20}: {} points, cluster angle {} sr: {:.2f} s ({:.2f} s the image), {:.0f} "
            "evaluations per pixel; relative error to the reference per pixel: median {:.3f}, "
            "90th percentile {:.3f}, mean signed {:+.3f}; in 4 x 4 blocks: median {:.3f}, 90th "
            "percentile {:.3f}, mean signed {:+.3f}\n",
            to_string(model), s.cloud.points, s.cluster_angle, r.seconds(), r.seconds_image,
            static_cast<double>(r.counters.evaluations) /
                static_cast<double>(std::max<std::uint64_t>(r.counters.eye_rays, 1)),
            e.median, e.p90, e.mean_signed, e4.median, e4.p90, e4.mean_signed);
        for (int c = 0; c < channels; ++c) {
          const ErrorStats ec = relative_error(r.image, multiple, mask, c + 1, 4, c);
          fmt::print("{:>20}  channel {}: 4 x 4 blocks median {:.3f}, mean signed {:+.3f}\n", "", c,
                     ec.median, ec.mean_signed);
        }
        std::fflush(stdout);
        hdf5::Group g = models.create_group(to_string(model));
        write_image(g, "image", r.image, radiance_units);
        g.write_double_attribute("seconds", r.seconds());
        g.write_double_attribute("seconds_image", r.seconds_image);
        g.write_double_attribute("error_median", e.median);
        g.write_double_attribute("error_p90", e.p90);
        g.write_double_attribute("error_mean_signed", e.mean_signed);
        g.write_double_attribute("error_block4_median", e4.median);
        g.write_double_attribute("error_block4_p90", e4.p90);
        g.write_double_attribute("error_block4_mean_signed", e4.mean_signed);
        g.write_int64_attribute("points", s.cloud.points);
        g.write_double_attribute("cluster_angle", s.cluster_angle);
      }
    }

    // The sweep: better dipole, points x cluster angle.
    const std::vector<int> point_counts =
        quick ? std::vector<int>{256, 1024} : std::vector<int>{1024, 4096, 16384, 65536};
    const std::vector<double> angles = {0.0, 0.01, 0.03, 0.1, 0.3, 1.0};
    struct Row {
      int points;
      double angle, seconds_image, seconds_total, evaluations;
      ErrorStats to_converged, to_reference;
    };
    std::vector<Row> rows;
    std::vector<BssrdfResult> results;
    RgbImage converged;
    for (auto n = point_counts.rbegin(); sweep_runs && n != point_counts.rend(); ++n) {
      for (const double angle : angles) {
        BssrdfSettings s;
        s.cloud.points = *n;
        s.cluster_angle = angle;
        s.threads = threads;
        const BssrdfResult r = render_bssrdf(scene, s);
        if (n == point_counts.rbegin() && angle == 0.0) converged = r.image;
        Row row{*n,
                angle,
                r.seconds_image,
                r.seconds(),
                static_cast<double>(r.counters.evaluations) /
                    static_cast<double>(std::max<std::uint64_t>(r.counters.eye_rays, 1)),
                relative_error(r.image, converged, mask, channels),
                relative_error(r.image, multiple, mask, channels, 4)};
        fmt::print(
            "sweep: {:>6} points, angle {:>5} sr: image {:8.3f} s, {:9.0f} evaluations per pixel; "
            "error to converged median {:.2e} p90 {:.2e}; to reference (4 x 4 blocks) median "
            "{:.3f} "
            "p90 {:.3f}\n",
            row.points, row.angle, row.seconds_image, row.evaluations, row.to_converged.median,
            row.to_converged.p90, row.to_reference.median, row.to_reference.p90);
        std::fflush(stdout);
        rows.push_back(row);
      }
    }
    {
      std::ofstream csv(out / "bssrdf_sweep.csv");
      csv << "points,cluster_angle,seconds_image,seconds_total,evaluations_per_pixel,"
             "converged_median,converged_p90,reference_median,reference_p90\n";
      for (const Row& r : rows) {
        csv << fmt::format("{},{},{},{},{},{},{},{},{}\n", r.points, r.angle, r.seconds_image,
                           r.seconds_total, r.evaluations, r.to_converged.median,
                           r.to_converged.p90, r.to_reference.median, r.to_reference.p90);
      }
    }
    hdf5::Group sweep = root.create_group("sweep");
    const auto column = [&](auto get) {
      std::vector<double> v;
      for (const Row& r : rows) v.push_back(get(r));
      return v;
    };
    sweep.write_dataset("points", column([](const Row& r) { return double(r.points); }));
    sweep.write_dataset("cluster_angle", column([](const Row& r) { return r.angle; }))
        .write_string_attribute("units", "sr");
    sweep.write_dataset("seconds_image", column([](const Row& r) { return r.seconds_image; }))
        .write_string_attribute("units", "s");
    sweep.write_dataset("converged_median",
                        column([](const Row& r) { return r.to_converged.median; }));
    sweep.write_dataset("converged_p90", column([](const Row& r) { return r.to_converged.p90; }));
    sweep.write_dataset("reference_median",
                        column([](const Row& r) { return r.to_reference.median; }));
    sweep.write_dataset("reference_p90", column([](const Row& r) { return r.to_reference.p90; }));
  }
  file.close();
  fmt::print("wrote {} and {}\n", (out / "bssrdf_comparison.h5").string(),
             (out / "bssrdf_sweep.csv").string());
  return 0;
}
