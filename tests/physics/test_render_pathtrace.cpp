// The path-traced single-scatter reference (method d) against the deterministic refractive
// methods on a scene with a small sphere light: agreement within k sigma (fixed seed), on a
// convex tile and on two tiles one above the other, where the upper one shadows the lower.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/render/render_scene.hpp"
#include "scatterlab/render/single_scatter_renderer.hpp"

namespace scatterlab {
namespace {

// A small sphere light over `mesh`, the medium and index of both tests, 8 x 8 pixels.
RenderScene lit_scene(TriangleMesh mesh, const Vec3& light, const Vec3& camera, const Vec3& look_at,
                      double fov_degrees) {
  RenderScene scene;
  scene.mesh = std::move(mesh);
  scene.medium = Medium::from_coefficients(0.05, 0.5, 0.2, "mesh units");
  scene.eta = 1.5;
  scene.light.position = light;
  scene.light.radius = 0.15;
  scene.camera.position = camera;
  scene.camera.look_at = look_at;
  scene.camera.up = Vec3::UnitZ();
  scene.camera.fov_degrees = fov_degrees;
  scene.width = 8;
  scene.height = 8;
  scene.light_samples = 24;  // points on the sphere light's disc
  scene.samples = 8;
  scene.validate();
  return scene;
}

struct Agreement {
  int lit_pixels = 0;
  RenderCounters deterministic;  // the deterministic render's work and paths
};

// `deterministic` against path tracing over the whole image and pixel by pixel.
Agreement expect_agreement(RenderScene scene, RenderMethod deterministic_method) {
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
  return {lit, reference.counters};
}

TEST(RenderPathtrace, ConvergesToTheRefractiveSolution) {
  const RenderScene scene =
      lit_scene(make_rounded_tile(1.0, 1.0, 0.25, 0.3, 12, 24), Vec3(0.0, 1.5, 2.5),
                Vec3(0.0, -3.5, 2.5), Vec3::Zero(), 40.0);
  EXPECT_GT(expect_agreement(scene, RenderMethod::holzschuch).lit_pixels, 10);
}

// Two tiles, the upper one shifted aside over the lower: light reaches the lower one past the
// upper, and through it by no path of one refraction. Without the visibility of both legs of a
// refracted path, walter and holzschuch light the lower tile through the upper one: paths that
// refract at the upper tile's top and run down through both, or refract at the lower tile's top
// under the upper one.
TEST(RenderPathtrace, AgreesOnAShapeThatShadowsItself) {
  const TriangleMesh tile = make_rounded_tile(1.0, 1.0, 0.25, 0.3, 12, 24);
  TriangleMesh tiles = tile;
  append_mesh(tiles, tile, Vec3(0.6, 0.0, 0.8));
  const RenderScene scene = lit_scene(std::move(tiles), Vec3(0.3, 0.4, 3.0), Vec3(0.3, -3.5, 1.6),
                                      Vec3(0.3, 0.0, 0.35), 36.0);
  for (const RenderMethod method : {RenderMethod::walter, RenderMethod::holzschuch}) {
    const Agreement agreement = expect_agreement(scene, method);
    EXPECT_GT(agreement.lit_pixels, 10);
    // The scene has teeth: a good part of the paths found are blocked.
    EXPECT_GT(agreement.deterministic.blocked_paths, agreement.deterministic.paths / 5)
        << to_string(method);
  }
}

}  // namespace
}  // namespace scatterlab
