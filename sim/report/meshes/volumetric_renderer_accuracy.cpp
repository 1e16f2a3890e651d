// The volumetric path tracer (render/volumetric_renderer.hpp) against what it must give exactly:
//  - an absorbing, index-matched sphere mesh seen against an environment of radiance L_e:
//    each eye ray keeps L_e e^{-sigma_a c}, c its chord through the polyhedron itself (traced
//    here with the mesh's ray tracer), so the image's mean is known exactly;
//  - the white furnace: with the light and the environment both of radiance L_e and a medium
//    that does not absorb (albedo 1), every path leaves with L_e whatever it meets (scattering,
//    Fresnel reflection and refraction each conserve energy), so every pixel is exactly L_e and
//    no path is lost, with the facets' geometric normals and with interpolated shading normals
//    (the boundary is the facets' either way).

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/mesh/mesh_ray_tracer.hpp"
#include "scatterlab/render/render_scene.hpp"
#include "scatterlab/render/volumetric_renderer.hpp"
#include "scatterlab/report/suites.hpp"
#include "simulation_checks.hpp"

namespace scatterlab::report {
namespace {

// A sphere mesh of radius 1 (16 rings, 32 segments) seen from -y by a small image, a sphere
// light above it out of view, and the environment: both of radiance `radiance`.
RenderScene furnace_scene(double sigma_a, double sigma_s, double g, double eta, double radiance,
                          bool shading_normals, int side) {
  RenderScene scene;
  scene.mesh = make_sphere(1.0, 16, 32, shading_normals);
  scene.medium = Medium::from_coefficients(sigma_a, sigma_s, g, "mesh units");
  scene.eta = eta;
  scene.environment_radiance = radiance;
  scene.light.position = Vec3(0.3, 0.5, 4.0);
  scene.light.radius = 0.4;
  scene.light.intensity = radiance * pi * scene.light.radius * scene.light.radius;  // L_e
  scene.camera.fov_degrees = 34.0;
  scene.width = side;
  scene.height = side;
  return scene;
}

RenderSettings volumetric(std::uint64_t seed, const Profile& profile) {
  RenderSettings settings;
  settings.method = RenderMethod::volumetric;
  settings.seed = seed;
  settings.threads = profile.threads;
  return settings;
}

// The mean over the image and its standard error (the pixels' paths are independent).
Estimate image_mean(const VolumetricResult& result) {
  const std::vector<double>& values = result.image.channels[0].values;
  const std::vector<double>& errors = result.standard_error.channels[0].values;
  double sum = 0.0, variance = 0.0;
  for (std::size_t k = 0; k < values.size(); ++k) {
    sum += values[k];
    variance += errors[k] * errors[k];
  }
  const auto n = static_cast<double>(values.size());
  return {sum / n, std::sqrt(variance) / n};
}

}  // namespace

Section volumetric_renderer_convergence(const Profile& profile) {
  Section section;
  section.id = "volumetric_renderer_convergence";
  section.title = "Volumetric renderer: error against run time";
  constexpr double radiance = 1.0, sigma_a = 0.8;
  constexpr int side = 10;
  RenderScene scene = furnace_scene(sigma_a, 0.0, 0.0, 1.0, radiance, false, side);
  scene.light.position = Vec3(0.0, 0.0, 40.0);  // far out of the image
  scene.validate();
  // Each eye ray's exact radiance: L_e e^{-sigma_a c}, c from the first crossing (entering) to
  // the next (leaving) of the convex polyhedron.
  const MeshRayTracer tracer(scene.mesh);
  double exact = 0.0;
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i) {
      const Vec3 way = scene.camera.ray_direction(i, j, side, side);
      const Vec3& eye = scene.camera.position;
      MeshHit in, out;
      double chord = 0.0;
      const double far = std::numeric_limits<double>::infinity();
      if (tracer.intersect(eye, way, 0.0, far, in) &&
          tracer.intersect(eye, way, in.distance + tracer.epsilon(), far, out)) {
        chord = out.distance - in.distance;
      }
      exact += radiance * std::exp(-sigma_a * chord) / (side * side);
    }
  }
  section.reference = fmt::format(
      "An absorbing sphere mesh (16 rings, sigma_a {} per unit, index matched) against an "
      "environment of radiance {}: the mean over a {} x {} image of L_e e^(-sigma_a c), c each "
      "eye ray's chord through the polyhedron, = {:.9f}.",
      sigma_a, radiance, side, side, exact);
  section.tolerance =
      "Each budget within 5 standard errors of the exact mean; the standard error falls as "
      "N^-1/2 (slope in [-0.6, -0.4]).";
  add_error_against_run_time(
      section, profile, {{"image_mean", "the image's mean radiance", exact}},
      "Volumetric renderer, absorbing sphere mesh",
      [&](std::uint64_t paths, std::uint64_t seed) {
        scene.samples = static_cast<int>(paths / (side * side));
        const VolumetricResult result = render_volumetric(scene, volumetric(seed, profile));
        return scalar_output(result.seconds, {{"image_mean", image_mean(result)}});
      },
      {"paths", "paths"});
  return section;
}

Section volumetric_renderer_extremes(const Profile& profile) {
  Section section;
  section.id = "volumetric_renderer_extremes";
  section.title = "Volumetric renderer: energy conservation (white furnace)";
  section.reference =
      "The white furnace: a sphere mesh that does not absorb (sigma_s 2 per unit), with the "
      "light and the environment both of radiance 2.5, shows 2.5 in every pixel; no path is "
      "lost, with geometric and with interpolated normals.";
  section.tolerance =
      "No lost path; every pixel within 5 standard errors of 2.5, plus 1e-12 (a path's weight "
      "changes only at Bitterli's roulette past 256 collisions, so most pixels are exact). No "
      "NaN or Inf.";
  section.table.columns = {"normals",
                           "eta",
                           "g",
                           "paths",
                           "seconds",
                           "lost",
                           "collisions",
                           "boundary_events",
                           "worst_pixel_deviation",
                           "worst_pixel_z"};
  constexpr double radiance = 2.5;
  constexpr int side = 6;
  const int samples = profile.quick ? 300 : 3000;
  for (const bool shading : {false, true}) {
    for (const double eta : {1.0, 1.0001, 1.5, 2.5}) {
      for (const double g : {-0.999, 0.0, 0.999}) {
        RenderScene scene = furnace_scene(0.0, 2.0, g, eta, radiance, shading, side);
        scene.samples = samples;
        scene.validate();
        const std::uint64_t seed = profile.seed + section.table.rows.size();
        const VolumetricResult result = render_volumetric(scene, volumetric(seed, profile));
        double worst = 0.0, worst_z = 0.0;
        bool within = true;
        const std::vector<double>& values = result.image.channels[0].values;
        const std::vector<double>& errors = result.standard_error.channels[0].values;
        for (std::size_t k = 0; k < values.size(); ++k) {
          section.non_finite_values += !std::isfinite(values[k]) + !std::isfinite(errors[k]);
          const double deviation = values[k] - radiance;
          within &= std::abs(deviation) <= 5.0 * errors[k] + 1e-12 * radiance;
          if (std::abs(deviation) > std::abs(worst)) worst = deviation;
          if (errors[k] > 0.0) worst_z = std::max(worst_z, std::abs(deviation) / errors[k]);
        }
        const std::string normals = shading ? "interpolated" : "geometric";
        const std::string cell = fmt::format("{} normals, eta {}, g {}", normals, eta, g);
        section.checks.push_back({fmt::format("{}: {} of {} paths lost", cell, result.counters.lost,
                                              result.counters.paths),
                                  result.counters.lost == 0});
        section.checks.push_back(
            {fmt::format("{}: worst pixel off by {:.2g} ({:.2f} standard errors)", cell, worst,
                         worst_z),
             within});
        section.table.rows.push_back(
            {normals, fmt::format("{}", eta), fmt::format("{}", g),
             fmt::format("{}", result.counters.paths), fmt::format("{:.3g}", result.seconds),
             fmt::format("{}", result.counters.lost), fmt::format("{}", result.counters.collisions),
             fmt::format("{}", result.counters.boundary), fmt::format("{:.2g}", worst),
             fmt::format("{:.2f}", worst_z)});
      }
    }
  }
  section.findings = checks_over_cells(section);
  return section;
}

}  // namespace scatterlab::report
