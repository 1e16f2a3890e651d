// The path-traced single-scatter reference (method d) against the deterministic refractive
// methods on a scene with a small sphere light: agreement within k sigma (fixed seed), on a
// convex tile and on two tiles one above the other, where the upper one shadows the lower.
#include <gtest/gtest.h>

#include <cmath>

#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/render/render_scene.hpp"
#include "scatterlab/render/single_scatter_renderer.hpp"

namespace scatterlab {
namespace {

// `deterministic` against path tracing over the whole image and pixel by pixel; the number of
// lit pixels.
int expect_agreement(RenderScene scene, RenderMethod deterministic_method) {
  RenderSettings deterministic;
  deterministic.method = deterministic_method;
  const RenderResult reference = render_single_scatter(scene, deterministic);

  scene.samples = 150000;
  RenderSettings pathtrace;
  pathtrace.method = RenderMethod::pathtrace;
  pathtrace.seed = 7;
  const RenderResult traced = render_single_scatter(scene, pathtrace);

  // Whole image: the sum of pixels, sigma from the per-pixel standard errors.
  double ref_sum = 0.0, mc_sum = 0.0, var_sum = 0.0;
  int outside_4_sigma = 0, lit = 0;
  for (std::size_t k = 0; k < traced.image.values.size(); ++k) {
    ref_sum += reference.image.values[k];
    mc_sum += traced.image.values[k];
    const double se = traced.standard_error.values[k];
    var_sum += se * se;
    if (se > 0.0) {
      ++lit;
      // 4 sigma, plus 2 % for the discretised light and the stratified midpoints of the
      // deterministic reference.
      if (std::abs(traced.image.values[k] - reference.image.values[k]) >
          4.0 * se + 0.02 * reference.image.values[k]) {
        ++outside_4_sigma;
      }
    }
  }
  EXPECT_GT(ref_sum, 0.0);
  const double sigma = std::sqrt(var_sum);
  EXPECT_LT(sigma, 0.05 * ref_sum);  // the comparison has teeth
  EXPECT_NEAR(mc_sum, ref_sum, 4.0 * sigma + 0.01 * ref_sum) << to_string(deterministic_method);
  EXPECT_LE(outside_4_sigma, 1) << "of " << lit << " lit pixels, "
                                << to_string(deterministic_method);
  return lit;
}

TEST(RenderPathtrace, ConvergesToTheRefractiveSolution) {
  RenderScene scene;
  scene.mesh = make_rounded_tile(1.0, 1.0, 0.25, 0.3, 12, 24);
  scene.medium = Medium::from_coefficients(0.05, 0.5, 0.2, "mesh units");
  scene.eta = 1.5;
  scene.light.position = Vec3(0.0, 1.5, 2.5);
  scene.light.radius = 0.15;
  scene.camera.position = Vec3(0.0, -3.5, 2.5);
  scene.camera.look_at = Vec3::Zero();
  scene.camera.up = Vec3::UnitZ();
  scene.camera.fov_degrees = 40.0;
  scene.width = 8;
  scene.height = 8;
  scene.light_samples = 24;  // points on the sphere light's disc
  scene.samples = 8;
  scene.validate();
  EXPECT_GT(expect_agreement(scene, RenderMethod::holzschuch), 10);
}

// Two tiles, the upper one shifted aside over the lower: light reaches the lower one past the
// upper, and through it by no path of one refraction. Without the visibility of both legs of a
// refracted path, walter and holzschuch light the lower tile through the upper one: paths that
// refract at the upper tile's top and run down through both, or refract at the lower tile's top
// under the upper one.
TEST(RenderPathtrace, AgreesOnAShapeThatShadowsItself) {
  RenderScene scene;
  const TriangleMesh tile = make_rounded_tile(1.0, 1.0, 0.25, 0.3, 12, 24);
  scene.mesh = tile;
  append_mesh(scene.mesh, tile, Vec3(0.6, 0.0, 0.8));
  scene.medium = Medium::from_coefficients(0.05, 0.5, 0.2, "mesh units");
  scene.eta = 1.5;
  scene.light.position = Vec3(0.3, 0.4, 3.0);
  scene.light.radius = 0.15;
  scene.camera.position = Vec3(0.3, -3.5, 1.6);
  scene.camera.look_at = Vec3(0.3, 0.0, 0.35);
  scene.camera.up = Vec3::UnitZ();
  scene.camera.fov_degrees = 36.0;
  scene.width = 8;
  scene.height = 8;
  scene.light_samples = 24;
  scene.samples = 8;
  scene.validate();

  for (const RenderMethod method : {RenderMethod::walter, RenderMethod::holzschuch}) {
    RenderSettings settings;
    settings.method = method;
    const RenderResult result = render_single_scatter(scene, settings);
    // The scene has teeth: a good part of the paths found are blocked.
    EXPECT_GT(result.counters.blocked_paths, result.counters.paths / 5) << to_string(method);
    EXPECT_GT(expect_agreement(scene, method), 10);
  }
}

}  // namespace
}  // namespace scatterlab
