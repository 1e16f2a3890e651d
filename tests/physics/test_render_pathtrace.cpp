// The path-traced single-scatter reference (method d) against the deterministic refractive
// methods on a scene with a small sphere light: agreement within k sigma (fixed seed).
#include <gtest/gtest.h>

#include <cmath>

#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/render/render_scene.hpp"
#include "scatterlab/render/single_scatter_renderer.hpp"

namespace scatterlab {
namespace {

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

  RenderSettings deterministic;
  deterministic.method = RenderMethod::holzschuch;
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
  ASSERT_GT(lit, 10);
  ASSERT_GT(ref_sum, 0.0);
  const double sigma = std::sqrt(var_sum);
  EXPECT_LT(sigma, 0.05 * ref_sum);  // the comparison has teeth
  EXPECT_NEAR(mc_sum, ref_sum, 4.0 * sigma + 0.01 * ref_sum);
  EXPECT_LE(outside_4_sigma, 1) << "of " << lit << " lit pixels";
}

}  // namespace
}  // namespace scatterlab
