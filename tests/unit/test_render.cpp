// The single-scatter renderer: a flat slab against the exact once-scattered radiance and against
// Jensen's straight-line approximation, the support-interval method against Walter's sample
// points, the specialised paths against the general one, and bad scenes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "input_error_field.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/memory_budget.hpp"
#include "scatterlab/core/phase_function.hpp"
#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/core/quadrature.hpp"
#include "scatterlab/render/render_scene.hpp"
#include "scatterlab/render/render_study.hpp"
#include "scatterlab/render/single_scatter_renderer.hpp"

namespace scatterlab {
namespace {

// A box much wider than deep, seen from above at an angle: the top face is a flat half-space
// boundary for the pixels near its centre.
RenderScene slab_scene(double eta) {
  RenderScene scene;
  scene.mesh = make_box(Vec3(6.0, 6.0, 1.0));
  scene.medium = Medium::from_coefficients(0.2, 0.8, 0.4, "mesh units");
  scene.eta = eta;
  scene.light.position = Vec3(0.4, 0.7, 2.5);
  scene.light.intensity = 2.0;
  scene.camera.position = Vec3(0.0, -2.0, 3.5);
  scene.camera.look_at = Vec3(0.0, 0.2, 1.0);
  scene.camera.up = Vec3::UnitZ();
  scene.camera.fov_degrees = 20.0;
  scene.width = 4;
  scene.height = 4;
  scene.samples = 400;
  scene.light_samples = 1;
  scene.validate();
  return scene;
}

// One pixel of the slab, independent of the renderer's machinery: the eye ray refracts at the
// plane z = h (Snell, Fresnel) and the once-scattered light along it, sigma_s exp(-sigma_t x)
// times `scattered`(V, w) (the phase function times the irradiance, for the eye ray's direction
// w inside), is integrated by adaptive Gauss-Kronrod.
template <class Scattered>
double slab_pixel(const RenderScene& scene, int i, int j, const Scattered& scattered) {
  const double h = 1.0, eta = scene.eta;
  const Vec3 c = scene.camera.position;
  const Vec3 d = scene.camera.ray_direction(i, j, scene.width, scene.height);
  const Vec3 p0 = c + ((h - c.z()) / d.z()) * d;
  const double cos_i = -d.z();
  const double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
  const double cos_t = std::sqrt(1.0 - sin2_t);
  const Vec3 w = (d / eta + (cos_i / eta - cos_t) * Vec3::UnitZ()).normalized();
  const double t_exit = (2.0 * h) / -w.z();  // through the bottom z = -h
  const auto integrand = [&](double x) {
    return scene.medium.sigma_s() * std::exp(-scene.medium.sigma_t * x) * scattered(p0 + x * w, w);
  };
  QuadratureOptions options;
  options.rel_tol = 1e-10;
  const double inside = integrate_adaptive(integrand, 0.0, t_exit, options).value;
  return fresnel_dielectric_transmittance(cos_i, eta) / (eta * eta) * inside;
}

// The exact once-scattered radiance: the light's refraction point is found by bisection on
// Snell's law in the plane of incidence, and D is Walter eq. 18 with eta (path_contribution.hpp).
double slab_exact(const RenderScene& scene, int i, int j) {
  const double h = 1.0, eta = scene.eta;
  const Vec3 light = scene.light.position;
  const double height = light.z() - h;
  const HenyeyGreenstein phase{scene.medium.g};
  return slab_pixel(scene, i, j, [&](const Vec3& v, const Vec3& w) {
    const double depth = h - v.z();
    const Vec3 horizontal(light.x() - v.x(), light.y() - v.y(), 0.0);
    const double rho = horizontal.norm();
    // Snell: (rho - r) / d_L = eta r / d_V, decreasing in r on [0, rho].
    double lo = 0.0, hi = rho;
    for (int k = 0; k < 200; ++k) {
      const double r = 0.5 * (lo + hi);
      const double f = (rho - r) / std::hypot(rho - r, height) - eta * r / std::hypot(r, depth);
      (f > 0.0 ? lo : hi) = r;
    }
    const double r = 0.5 * (lo + hi);
    const double d_v = std::hypot(r, depth), d_l = std::hypot(rho - r, height);
    const double cos_v = depth / d_v, cos_l = height / d_l;
    const double big_d = (d_v + eta * d_l) * (d_v * cos_l / cos_v + eta * d_l * cos_v / cos_l);
    const Vec3 p =
        v + (rho > 0.0 ? Vec3(horizontal * (r / rho)) : Vec3::Zero()) + Vec3(0.0, 0.0, depth);
    const Vec3 omega_v = (v - p) / d_v;
    const double irradiance = fresnel_dielectric_transmittance(cos_l, eta) * eta * eta / big_d *
                              std::exp(-scene.medium.sigma_t * d_v);
    return phase.evaluate(-omega_v.dot(w)) * scene.light.intensity * irradiance;
  });
}

// Jensen et al. 2001, §4.3 on the slab, as printed: the straight line from V to the light meets
// the plane z = h after s_i at cosine mu; the refracted distance is
// s_i' = s_i mu / sqrt(1 - (1 / eta)^2 (1 - mu^2)), and the phase function takes the refracted
// direction omega_i', whose horizontal part is the straight line's over eta (Snell).
double slab_jensen(const RenderScene& scene, int i, int j) {
  const double h = 1.0, eta = scene.eta;
  const HenyeyGreenstein phase{scene.medium.g};
  return slab_pixel(scene, i, j, [&](const Vec3& v, const Vec3& w) {
    const Vec3 to_light = scene.light.position - v;
    const double distance = to_light.norm();
    const Vec3 u = to_light / distance;
    const double mu = u.z(), s_i = (h - v.z()) / mu;
    const double cos2_t = 1.0 - (1.0 - mu * mu) / (eta * eta);
    if (cos2_t <= 0.0) return 0.0;  // light from outside totally reflected (eta < 1)
    const double mu_t = std::sqrt(cos2_t);
    const Vec3 omega_i(-u.x() / eta, -u.y() / eta, -mu_t);  // the light's travel inside
    const double irradiance = fresnel_dielectric_transmittance(mu, eta) *
                              std::exp(-scene.medium.sigma_t * s_i * mu / mu_t) /
                              (distance * distance);
    return phase.evaluate(-omega_i.dot(w)) * scene.light.intensity * irradiance;
  });
}

// walter and holzschuch against the exact once-scattered radiance, straight against Jensen's
// formula as printed.
TEST(Render, FlatSlabMatchesIndependentEvaluations) {
  for (const double eta : {1.5, 0.8}) {
    const RenderScene scene = slab_scene(eta);
    for (const RenderMethod method :
         {RenderMethod::walter, RenderMethod::holzschuch, RenderMethod::straight}) {
      RenderSettings settings;
      settings.method = method;
      const RenderResult result = render_single_scatter(scene, settings);
      for (int j = 0; j < scene.height; ++j) {
        for (int i = 0; i < scene.width; ++i) {
          const double expected =
              method == RenderMethod::straight ? slab_jensen(scene, i, j) : slab_exact(scene, i, j);
          ASSERT_GT(expected, 0.0);
          // Midpoint rule in the transmittance CDF, 400 points: O(1 / N^2).
          EXPECT_NEAR(result.image.at(i, j), expected, 2e-4 * expected)
              << "eta " << eta << " method " << to_string(method) << " pixel " << i << "," << j;
        }
      }
    }
  }
}

RenderScene small_bumpy_scene() {
  RenderScene scene;
  scene.mesh = make_bumpy_sphere(1.0, 0.08, 4, 12, 12);
  scene.medium = Medium::from_coefficients(0.05, 0.5, 0.3, "mesh units");
  scene.eta = 1.4;
  scene.light.position = Vec3(0.3, 3.0, 0.6);
  scene.camera.position = Vec3(0.0, -4.0, 0.3);
  scene.camera.look_at = Vec3::Zero();
  scene.camera.up = Vec3::UnitZ();
  scene.camera.fov_degrees = 25.0;
  scene.width = 6;
  scene.height = 6;
  scene.samples = 6;
  scene.light_samples = 1;
  scene.validate();
  return scene;
}

TEST(Render, SupportIntervalsAtWalterPointsGiveWalterImage) {
  RenderScene scene = small_bumpy_scene();
  scene.samples = 3;  // the identity holds point by point; few points keep sanitizer runs short
  RenderSettings walter;
  walter.method = RenderMethod::walter;
  RenderSettings holzschuch;
  holzschuch.method = RenderMethod::holzschuch;
  holzschuch.shared_points = true;
  const RenderResult a = render_single_scatter(scene, walter);
  const RenderResult b = render_single_scatter(scene, holzschuch);
  double total = 0.0;
  for (std::size_t k = 0; k < a.image.values.size(); ++k) {
    total += a.image.values[k];
    EXPECT_NEAR(b.image.values[k], a.image.values[k], 1e-12 * a.image.values[k] + 1e-300) << k;
  }
  EXPECT_GT(total, 0.0);
  EXPECT_GT(a.counters.triangle_searches, b.counters.triangle_searches);
}

TEST(Render, SpecialisedPathsGiveTheGeneralImage) {
  // eta = 1 (no refraction) and flat facets (no shading normals) against the general kernel.
  RenderScene scene = small_bumpy_scene();
  scene.mesh.normals.clear();
  scene.eta = 1.0;
  for (const RenderMethod method :
       {RenderMethod::straight, RenderMethod::walter, RenderMethod::holzschuch}) {
    RenderSettings fast;
    fast.method = method;
    RenderSettings general = fast;
    general.force_general = true;
    const RenderResult a = render_single_scatter(scene, fast);
    const RenderResult b = render_single_scatter(scene, general);
    double total = 0.0;
    for (std::size_t k = 0; k < a.image.values.size(); ++k) {
      total += a.image.values[k];
      EXPECT_NEAR(b.image.values[k], a.image.values[k], 1e-9 * a.image.values[k]) << k;
    }
    EXPECT_GT(total, 0.0) << to_string(method);
  }
}

TEST(Render, StraightLineIsExactWhenNothingRefracts) {
  // With eta = 1 the straight shadow ray is the refracted path: methods (a) and (b) agree.
  RenderScene scene = small_bumpy_scene();
  scene.eta = 1.0;
  RenderSettings straight;
  straight.method = RenderMethod::straight;
  RenderSettings walter;
  walter.method = RenderMethod::walter;
  const RenderResult a = render_single_scatter(scene, straight);
  const RenderResult b = render_single_scatter(scene, walter);
  for (std::size_t k = 0; k < a.image.values.size(); ++k) {
    EXPECT_NEAR(a.image.values[k], b.image.values[k], 1e-6 * b.image.values[k]) << k;
  }
}

std::string error_of(const std::string& text, const std::filesystem::path& base = {}) {
  try {
    parse_render_scene(text, "test.toml", base);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Render, BadScenesGiveOneClearError) {
  EXPECT_EQ(error_of("[medium]\neta = 1.5\n").rfind("mesh: missing", 0), 0u);
  EXPECT_EQ(error_of("[mesh]\nshape = \"cube\"\n").rfind("mesh.shape:", 0), 0u);
  EXPECT_EQ(error_of("[mesh]\nshape = \"sphere\"\n[light]\nposition = [0, 0, 0.2]\n")
                .rfind("light.position: inside the object", 0),
            0u);
  EXPECT_EQ(error_of("[mesh]\nshape = \"sphere\"\n[medium]\neta = -1\n").rfind("medium.eta:", 0),
            0u);
  EXPECT_NE(
      error_of("[mesh]\nshape = \"sphere\"\n[light]\nradus = 1\n").find("did you mean \"radius\""),
      std::string::npos);
  const auto dir = std::filesystem::temp_directory_path() / "scatterlab_render_test";
  std::filesystem::create_directories(dir);
  {
    std::ofstream open_mesh(dir / "open.obj");
    open_mesh << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\n";
    std::ofstream nan_normals(dir / "nan.obj");
    nan_normals << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn nan 0 0\n"
                   "f 1//1 3//1 2//1\nf 1//1 2//1 4//1\nf 2//1 3//1 4//1\nf 1//1 4//1 3//1\n";
  }
  EXPECT_EQ(error_of("[mesh]\nshape = \"obj\"\npath = \"open.obj\"\n", dir)
                .rfind("mesh: not a closed", 0),
            0u);
  EXPECT_EQ(error_of("[mesh]\nshape = \"obj\"\npath = \"nan.obj\"\n", dir).rfind("mesh.path: ", 0),
            0u);
  EXPECT_NE(error_of("[mesh]\nshape = \"obj\"\npath = \"nan.obj\"\n", dir).find("not finite"),
            std::string::npos);
  {
    std::ofstream far_vertex(dir / "far.obj");
    far_vertex << "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n";
  }
  // tinyobjloader would read 1e999 as 0; the vertex lines are checked before it reads them.
  EXPECT_NE(error_of("[mesh]\nshape = \"obj\"\npath = \"far.obj\"\n", dir)
                .find("line 2: coordinate 1 of 'v' is '1e999', not finite"),
            std::string::npos);
  EXPECT_EQ(
      error_of("[mesh]\nshape = \"obj\"\npath = \"missing.obj\"\n", dir).rfind("mesh.path: ", 0),
      0u);
  std::filesystem::remove_all(dir);
  // A point light cannot feed the path-traced reference.
  RenderSettings pathtrace;
  pathtrace.method = RenderMethod::pathtrace;
  EXPECT_THROW(render_single_scatter(slab_scene(1.5), pathtrace), InputError);
  EXPECT_THROW(parse_render_method("jensen"), InputError);
}

// A procedural mesh's memory is checked before it is built: a sphere of 4096 x 4096 (33.5 million
// triangles) under --memory-limit 64M is refused at once, not built and checked in 10 GB first
// (tests/fuzz/corpus/scene/oom-mesh-rings-segments.toml).
TEST(Render, AMeshTooLargeForTheMemoryLimitIsRefusedBeforeItIsBuilt) {
  set_memory_limit(std::uint64_t{64} << 20, "64M");
  const std::string message =
      error_of("[mesh]\nshape = \"sphere\"\nrings = 4096\nsegments = 4096\n");
  const std::string tile = "[mesh]\nshape = \"rounded_tile\"\nrings = 4096\nsegments = 200\n";
  const std::string small = "[mesh]\nshape = \"sphere\"\nrings = 24\nsegments = 48\n";
  const std::string tile_field =
      test_support::field_of([&] { parse_scene_mesh(tile, "test.toml"); });
  const std::string small_field =
      test_support::field_of([&] { parse_scene_mesh(small, "test.toml"); });
  set_memory_limit(std::nullopt);
  EXPECT_EQ(message.rfind("mesh.rings x mesh.segments: ", 0), 0u) << message;
  EXPECT_NE(message.find("33554432 triangles"), std::string::npos) << message;
  EXPECT_NE(message.find("accepted: fewer rings or segments"), std::string::npos) << message;
  EXPECT_EQ(tile_field, "mesh.rings x mesh.segments");
  EXPECT_EQ(small_field, "");
}

TEST(Render, WorkIsPixelsTimesSamplesTimesLightPoints) {
  RenderScene scene;
  scene.width = 64;
  scene.height = 32;
  scene.samples = 8;
  scene.light_samples = 16;
  RenderSettings settings;
  settings.method = RenderMethod::holzschuch;
  EXPECT_EQ(render_evaluations(scene, settings), 64u * 32u * 8u * 16u);
  settings.method = RenderMethod::pathtrace;  // one light sample per path
  EXPECT_EQ(render_evaluations(scene, settings), 64u * 32u * 8u);
  EXPECT_NO_THROW(check_render_work(scene, settings));
  // Every size at its largest: 2^28 pixels x 2^20 samples x 2^12 light points = 2^60.
  scene.width = scene.height = max_image_side;
  scene.samples = max_samples;
  scene.light_samples = max_light_samples;
  settings.method = RenderMethod::walter;
  EXPECT_EQ(render_evaluations(scene, settings), std::uint64_t{1} << 60);
  EXPECT_THROW(check_render_work(scene, settings), InputError);
}

// The study's error measures on a 2 x 1 image: differences (0.3, -0.4) against (1, 0), first
// against an exact reference, then against one with standard errors (0.1, 0.2), whose variance
// 0.05 comes off the sum of squares 0.25 and off the reference's 1.
TEST(Render, StudyErrorsAreRmsAndRelativeL2LessTheReferenceNoise) {
  Image reference(2, 1), image(2, 1), exact(2, 1), noisy(2, 1);
  reference.values = {1.0, 0.0};
  image.values = {1.3, -0.4};
  noisy.values = {0.1, 0.2};
  ImageErrors errors = image_errors(image, reference, exact);
  EXPECT_NEAR(errors.rmse, std::sqrt(0.25 / 2.0), 1e-15);
  EXPECT_NEAR(errors.relative_error, 0.5, 1e-15);
  EXPECT_EQ(errors.reference_noise, 0.0);
  errors = image_errors(image, reference, noisy);
  EXPECT_NEAR(errors.rmse, std::sqrt(0.2 / 2.0), 1e-15);
  EXPECT_NEAR(errors.relative_error, std::sqrt(0.2 / 0.95), 1e-15);
  EXPECT_NEAR(errors.reference_noise, std::sqrt(0.05 / 0.95), 1e-15);
  // (2 (0.1^4 + 0.2^4))^(1/4) / sqrt(0.95)
  EXPECT_NEAR(errors.resolution, std::pow(2.0 * 0.0017, 0.25) / std::sqrt(0.95), 1e-15);
  // An error under the reference's noise is not resolved: 0.
  errors = image_errors(reference, reference, noisy);
  EXPECT_EQ(errors.rmse, 0.0);
  EXPECT_EQ(errors.relative_error, 0.0);
  EXPECT_THROW(image_errors(Image(1, 1), reference, exact), std::invalid_argument);
  EXPECT_THROW(image_errors(image, reference, Image(1, 1)), std::invalid_argument);
}

TEST(Render, ShippedScenesLoad) {
  const auto scenes = std::filesystem::path(SCATTERLAB_SOURCE_DIR) / "data" / "scenes";
  const RenderScene bumpy = load_render_scene(scenes / "bumpy-sphere.toml");
  EXPECT_EQ(bumpy.mesh.triangle_count(), 10080u);
  EXPECT_TRUE(bumpy.mesh.has_shading_normals());
  const RenderScene tile = load_render_scene(scenes / "tile.toml");
  EXPECT_GT(tile.light.radius, 0.0);
}

}  // namespace
}  // namespace scatterlab
