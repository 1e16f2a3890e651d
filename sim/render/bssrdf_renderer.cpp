#include "scatterlab/render/bssrdf_renderer.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <span>

#include "image_tiles.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/io/atomic_output.hpp"
#include "scatterlab/io/hdf5_file.hpp"
#include "scatterlab/mesh/mesh_ray_tracer.hpp"
#include "scatterlab/models/bssrdf.hpp"
#include "scatterlab/models/half_space_medium.hpp"
#include "scatterlab/render/point_octree.hpp"
#include "scatterlab/render/single_scatter_renderer.hpp"

namespace scatterlab {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The half-space medium of each channel: the scene's medium per channel, or the one medium.
std::vector<HalfSpaceMedium> channel_media(const RenderScene& scene) {
  std::vector<HalfSpaceMedium> media;
  const auto add = [&](const Medium& m) {
    media.push_back({m.sigma_a(), m.sigma_s(), m.g, scene.eta});
  };
  if (scene.channel_media.empty()) {
    add(scene.medium);
  } else {
    for (const Medium& m : scene.channel_media) add(m);
  }
  return media;
}

}  // namespace

void check_bssrdf_work(const RenderScene& scene, const BssrdfSettings& settings,
                       const std::string& field) {
  // Without clustering every pixel and every point sums every point.
  const auto pixels =
      static_cast<std::uint64_t>(scene.width) * static_cast<std::uint64_t>(scene.height);
  const auto n_points = static_cast<std::uint64_t>(std::max(settings.cloud.points, 0));
  if (settings.cluster_angle == 0.0 && (pixels + n_points) * n_points > max_render_evaluations) {
    throw InputError(
        field,
        fmt::format("0 with {} points and {} x {} pixels: {:.3g} evaluations", n_points,
                    scene.width, scene.height, static_cast<double>((pixels + n_points) * n_points)),
        "a cluster angle > 0 (a few hundred evaluations per pixel), fewer points or "
        "a smaller image");
  }
}

BssrdfResult render_bssrdf(const RenderScene& scene, const BssrdfSettings& settings,
                           const WorkProgress& progress) {
  refuse_volumetric_only(scene, "bssrdf");
  if (!(settings.cluster_angle >= 0.0) || !std::isfinite(settings.cluster_angle)) {
    throw InputError("cluster_angle", fmt::format("got {}", settings.cluster_angle),
                     "a solid angle >= 0 in sr (0: no clustering)");
  }
  check_bssrdf_work(scene, settings);
  check_bssrdf_eta(scene.eta, "medium.eta");
  // The profiles first: a medium they refuse is refused before any work.
  std::vector<DiffusionProfile> profiles;
  for (const HalfSpaceMedium& m : channel_media(scene)) profiles.emplace_back(settings.model, m);

  BssrdfResult result;
  result.channels = static_cast<int>(profiles.size());
  auto start = Clock::now();
  // Progress in steps: the relaxation's iterations, then the image's tiles.
  const auto relaxation = static_cast<std::uint64_t>(std::max(settings.cloud.relaxation, 0));
  const auto tiles = static_cast<std::uint64_t>((scene.width + 7) / 8) *
                     static_cast<std::uint64_t>((scene.height + 7) / 8);  // image_tiles.hpp
  WorkProgress cloud_progress, tile_progress;
  if (progress) {
    cloud_progress = [&](std::uint64_t done, std::uint64_t) { progress(done, relaxation + tiles); };
    tile_progress = [&](std::uint64_t done, std::uint64_t all) {
      progress(relaxation + done, relaxation + all);
    };
  }
  PointCloudOptions cloud_options = settings.cloud;
  cloud_options.threads = settings.threads;
  result.cloud = make_point_cloud(scene.mesh, cloud_options, cloud_progress);
  result.seconds_cloud = seconds_since(start);

  start = Clock::now();
  result.irradiance = point_irradiance(scene, result.cloud, settings.occlusion, settings.threads);
  result.seconds_irradiance = seconds_since(start);
  result.counters.lit_points = static_cast<std::uint64_t>(std::count_if(
      result.irradiance.begin(), result.irradiance.end(), [](double e) { return e > 0.0; }));

  start = Clock::now();
  const PointCloud& cloud = result.cloud;
  const PointOctree octree = cloud_octree(cloud, result.irradiance);
  const std::vector<RadialKernel> kernels =
      cloud_kernels(profiles, cloud.point_area, scene.mesh.bounds());
  result.octree_nodes = octree.node_count();
  result.octree_depth = octree.depth();
  result.seconds_octree = seconds_since(start);

  // The exitance at every point of the cloud.
  start = Clock::now();
  const auto channels = static_cast<std::size_t>(result.channels);
  result.exitance.assign(cloud.size() * channels, 0.0);
  const auto n = static_cast<std::ptrdiff_t>(cloud.size());
#pragma omp parallel for schedule(dynamic, 64) \
    num_threads(settings.threads > 0 ? settings.threads : omp_get_max_threads())
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    OctreeQuery query;
    const auto k = static_cast<std::size_t>(i);
    octree.exitance(cloud.positions[k], settings.cluster_angle, kernels,
                    std::span<double>(result.exitance).subspan(k * channels, channels), query);
  }
  result.seconds_points = seconds_since(start);

  // The image: one eye ray per pixel centre (the ray tracer's build is the octree step's).
  start = Clock::now();
  const MeshRayTracer tracer(scene.mesh);
  result.seconds_octree += seconds_since(start);
  start = Clock::now();
  result.image = RgbImage(scene.width, scene.height);
  const auto pixels = [&](int x0, int x1, int y0, int y1, BssrdfCounters& count) {
    std::array<double, max_kernel_channels> m{};
    for (int j = y0; j < y1; ++j) {
      for (int i = x0; i < x1; ++i) {
        const Vec3 d = scene.camera.ray_direction(i, j, scene.width, scene.height);
        MeshHit hit;
        if (!tracer.intersect(scene.camera.position, d, 0.0, 1e300, hit)) continue;
        const std::uint32_t t = hit.triangle;
        const double a = hit.bary_a, b = hit.bary_b;
        const Vec3 x = (1.0 - a - b) * scene.mesh.vertex(t, 0) + a * scene.mesh.vertex(t, 1) +
                       b * scene.mesh.vertex(t, 2);
        const Vec3 shading = (1.0 - a - b) * scene.mesh.corner_normal(t, 0) +
                             a * scene.mesh.corner_normal(t, 1) +
                             b * scene.mesh.corner_normal(t, 2);
        const double cos_out = std::clamp(-d.dot(shading.normalized()), 0.0, 1.0);
        OctreeQuery query;
        octree.exitance(x, settings.cluster_angle, kernels, std::span<double>(m.data(), channels),
                        query);
        const double weight = bssrdf_exit_weight(scene.eta, cos_out);
        for (std::size_t c = 0; c < 3; ++c) {
          result.image.channels[c].at(i, j) = weight * m[std::min(c, channels - 1)];
        }
        ++count.eye_rays;
        count.evaluations += query.evaluations;
        count.clusters += query.clusters;
      }
    }
  };
  for (const BssrdfCounters& c : render_tiles<BssrdfCounters>(
           scene.width, scene.height, settings.threads, tile_progress, pixels)) {
    result.counters.eye_rays += c.eye_rays;
    result.counters.evaluations += c.evaluations;
    result.counters.clusters += c.clusters;
  }
  result.seconds_image = seconds_since(start);
  return result;
}

void write_point_cloud_file(const std::filesystem::path& path, const RenderScene& scene,
                            const BssrdfSettings& settings, const BssrdfResult& result) {
  const std::string unit = scene.medium.length_unit;
  const PointCloud& cloud = result.cloud;
  const std::size_t n = cloud.size();
  std::vector<double> positions(3 * n), normals(3 * n), area(n, cloud.point_area);
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      positions[3 * i + static_cast<std::size_t>(k)] = cloud.positions[i][k];
      normals[3 * i + static_cast<std::size_t>(k)] = cloud.normals[i][k];
    }
  }
  AtomicOutput output(path);
  {
    hdf5::File file = hdf5::File::create(output.temporary_path());
    hdf5::Group& root = file.root();
    root.write_string_attribute("method", "bssrdf");
    root.write_string_attribute(
        "description",
        "Hierarchical point cloud (Jensen & Buhler 2002; Bitterli 2013 sec. 2.6.4): the power "
        "entering per unit area at each point and the multiple-scattering exitance of the "
        "diffusion profile there");
    {
      hdf5::Group parameters = root.create_group("parameters");
      parameters.write_string_attribute("model", to_string(settings.model));
      parameters.write_int64_attribute("points", static_cast<std::int64_t>(n));
      parameters.write_int64_attribute("relaxation", settings.cloud.relaxation);
      parameters.write_uint64_attribute("seed", settings.cloud.seed);
      parameters.write_double_attribute("cluster_angle", settings.cluster_angle);
      parameters.write_bool_attribute("occlusion", settings.occlusion);
      parameters.write_double_attribute("eta", scene.eta);
      parameters.write_double_attribute("light_intensity", scene.light.intensity);
      parameters.write_double_attribute("light_radius", scene.light.radius);
      parameters.write_int64_attribute("light_samples", scene.light_samples);
      parameters.write_string_attribute("length_unit", unit);
      parameters.write_int64_attribute("channels", result.channels);
    }
    hdf5::Group points = root.create_group("points");
    const auto with_units = [](hdf5::Dataset dataset, const std::string& units,
                               const std::string& description) {
      dataset.write_string_attribute("units", units);
      dataset.write_string_attribute("description", description);
    };
    with_units(points.write_dataset("position", positions, {n, 3}), unit,
               "point on the mesh surface");
    with_units(points.write_dataset("normal", normals, {n, 3}), "1", "unit outward shading normal");
    with_units(points.write_dataset("area", area), unit + "^2",
               "area each point stands for, A / N (the areas sum to the mesh's area)");
    with_units(points.write_dataset("irradiance", result.irradiance), "W " + unit + "^-2",
               "power entering the medium per unit area, E_t = sum F_t cos I / d^2 (I in W/sr)");
    with_units(points.write_dataset("exitance", result.exitance,
                                    {n, static_cast<std::size_t>(result.channels)}),
               "W " + unit + "^-2",
               "multiple-scattering exitance M = sum_p E_t A_p R_d(|x - p|), per channel "
               "(red, green, blue, or one)");
    file.close();
  }
  output.commit();
}

}  // namespace scatterlab
