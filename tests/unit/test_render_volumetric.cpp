// Volumetric path tracing (render/volumetric_renderer.hpp) against identities it must meet
// exactly, and against the single-scatter path tracer for its once-scattered part. Fixed seeds;
// every tolerance is k sigma with sigma the pixel's standard error, plus what the geometry's
// tessellation allows where stated.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "input_error_field.hpp"
#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/mesh/mesh_ray_tracer.hpp"
#include "scatterlab/render/render_scene.hpp"
#include "scatterlab/render/single_scatter_renderer.hpp"
#include "scatterlab/render/volumetric_renderer.hpp"

namespace scatterlab {
namespace {

using test_support::field_of;

// A unit sphere seen from -y, with a small sphere light above whose radiance is `radiance`.
RenderScene sphere_scene(double sigma_a, double sigma_s, double g, double eta, double radiance,
                         int rings, int segments, bool shading_normals = false) {
  RenderScene scene;
  scene.mesh = make_sphere(1.0, rings, segments, shading_normals);
  scene.medium = Medium::from_coefficients(sigma_a, sigma_s, g, "mesh units");
  scene.eta = eta;
  scene.light.position = Vec3(0.3, 0.5, 4.0);
  scene.light.radius = 0.4;
  // L_e = I / (pi r^2) (render_scene.hpp).
  scene.light.intensity = radiance * pi * scene.light.radius * scene.light.radius;
  scene.camera.position = Vec3(0.0, -4.0, 0.0);
  scene.camera.look_at = Vec3::Zero();
  scene.camera.up = Vec3::UnitZ();
  scene.camera.fov_degrees = 34.0;
  scene.width = 6;
  scene.height = 6;
  scene.samples = 200;
  return scene;
}

RenderSettings volumetric(std::uint64_t seed) {
  RenderSettings settings;
  settings.method = RenderMethod::volumetric;
  settings.seed = seed;
  return settings;
}

// White furnace. With the environment and the light both of radiance L_e, every direction
// outside the object carries L_e. A non-absorbing object (albedo 1) only redistributes light:
// the radiance leaving it along any ray is the integral of L_e against a kernel of total mass
// 1 (scattering, Fresnel reflection and transmission each conserve energy, and with no
// absorption every path leaves), so every pixel sees exactly L_e, through any eta. The n^2
// factors cancel on the way in and out. The tracer's weights are 1 (analog choices), so a pixel
// deviates only by lost paths or an energy error; tolerance 4 sigma (sigma 0 when no path
// deviates: then equality to rounding). A mesh with interpolated normals loses no path either:
// the boundary is the facets' (volumetric_renderer.cpp, cross_boundary).
void expect_furnace(double eta, bool shading_normals = false) {
  const double radiance = 2.5;
  RenderScene scene = sphere_scene(0.0, 2.0, 0.5, eta, radiance, 16, 32, shading_normals);
  scene.environment_radiance = radiance;
  scene.samples = 2000;
  scene.validate();
  const VolumetricResult result = render_volumetric(scene, volumetric(11));
  EXPECT_GT(result.counters.collisions, result.counters.paths);    // light did scatter
  EXPECT_GT(2 * result.counters.boundary, result.counters.paths);  // half the pixels see it
  EXPECT_EQ(result.counters.lost, 0u);
  for (int c = 0; c < 3; ++c) {
    for (std::size_t k = 0; k < result.image.channels[c].values.size(); ++k) {
      const double value = result.image.channels[c].values[k];
      const double se = result.standard_error.channels[c].values[k];
      EXPECT_NEAR(value, radiance, 4.0 * se + 1e-12 * radiance) << "eta " << eta << ", pixel " << k;
    }
  }
}

TEST(RenderVolumetric, WhiteFurnaceWithoutRefraction) {
  expect_furnace(1.0);
}

TEST(RenderVolumetric, WhiteFurnaceThroughFresnelBoundary) {
  expect_furnace(1.5);
}

TEST(RenderVolumetric, WhiteFurnaceThroughInterpolatedNormals) {
  expect_furnace(1.5, true);
}

// A purely absorbing sphere (albedo 0, eta = 1) against a uniform background of radiance L_e:
// Beer-Lambert along the eye ray, L = L_e exp(-sigma_t c), with the chord of a ray at distance b
// from the centre c = 2 sqrt(R^2 - b^2). The tessellated sphere is convex and lies between the
// sphere of radius R (its vertices) and that of its smallest facet distance R_in, so its chord
// lies between theirs; the tolerance is that band plus 4 sigma.
TEST(RenderVolumetric, AbsorbingSphereFollowsBeerLambert) {
  const double radiance = 1.5, sigma_a = 0.8;
  RenderScene scene = sphere_scene(sigma_a, 0.0, 0.0, 1.0, radiance, 96, 192);
  scene.environment_radiance = radiance;
  scene.light.position = Vec3(0.0, 0.0, 40.0);  // far from the image
  scene.width = 10;
  scene.height = 10;
  scene.samples = 10000;
  scene.validate();
  double r_in = 1.0;
  for (std::size_t t = 0; t < scene.mesh.triangle_count(); ++t) {
    const Vec3 n = scene.mesh.geometric_normal(t);
    r_in = std::min(r_in, std::abs(n.dot(scene.mesh.vertex(t, 0))));
  }
  ASSERT_GT(r_in, 0.999);
  const VolumetricResult result = render_volumetric(scene, volumetric(5));
  int inside = 0;
  for (int j = 0; j < scene.height; ++j) {
    for (int i = 0; i < scene.width; ++i) {
      const Vec3 d = scene.camera.ray_direction(i, j, scene.width, scene.height);
      const Vec3 to_centre = -scene.camera.position;
      const double b = (to_centre - to_centre.dot(d) * d).norm();
      const double value = result.image.channels[0].at(i, j);
      const double se = result.standard_error.channels[0].at(i, j);
      const auto chord = [b](double r) { return b < r ? 2.0 * std::sqrt(r * r - b * b) : 0.0; };
      const double low = radiance * std::exp(-sigma_a * chord(1.0));
      const double high = radiance * std::exp(-sigma_a * chord(r_in));
      if (b < 0.98) ++inside;
      EXPECT_GE(value, low - 4.0 * se - 1e-12) << "pixel " << i << ", " << j << ", b " << b;
      EXPECT_LE(value, high + 4.0 * se + 1e-12) << "pixel " << i << ", " << j << ", b " << b;
    }
  }
  EXPECT_GT(inside, 40);
}

// Fresnel reflection at the boundary: an opaque absorber (albedo 0, sigma_t so large that a
// refracted path dies within 1e-4 of the radius) of eta = 1.5 in a uniform environment L_e. A
// convex object cannot see itself, so a pixel's radiance is exactly F(cos theta_i, eta) L_e
// (Born & Wolf §1.5.2), with theta_i the angle between the eye ray and the facet it meets
// (flat facets: the renderer's normal). Tolerance 4 sigma (a Bernoulli mean of `samples`).
TEST(RenderVolumetric, OpaqueSphereShowsFresnelReflectance) {
  const double radiance = 3.0, eta = 1.5;
  RenderScene scene = sphere_scene(1e4, 0.0, 0.0, eta, radiance, 24, 48);
  scene.environment_radiance = radiance;
  scene.width = 9;
  scene.height = 9;
  scene.samples = 10000;
  scene.validate();
  const VolumetricResult result = render_volumetric(scene, volumetric(6));
  const MeshRayTracer tracer(scene.mesh);
  int seen = 0;
  for (int j = 0; j < scene.height; ++j) {
    for (int i = 0; i < scene.width; ++i) {
      const Vec3 d = scene.camera.ray_direction(i, j, scene.width, scene.height);
      MeshHit hit;
      double expected = radiance;  // the environment, or the light of the same radiance
      if (tracer.intersect(scene.camera.position, d, 0.0, 1e300, hit)) {
        const double cos_i = -d.dot(scene.mesh.geometric_normal(hit.triangle));
        expected = radiance * fresnel_dielectric_reflectance(cos_i, eta);
        ++seen;
      }
      const double se = result.standard_error.channels[0].at(i, j);
      EXPECT_NEAR(result.image.channels[0].at(i, j), expected, 4.0 * se + 1e-12)
          << "pixel " << i << ", " << j;
    }
  }
  EXPECT_GT(seen, 30);
}

// The floor under the sphere light alone: a Lambertian plane of albedo a lit by a sphere of
// radiance L_e, radius r, centre at distance D, wholly above the horizon, has the irradiance
// E = pi L_e (r / D)^2 cos theta_c (the sphere's form factor; cos theta_c the centre's angle
// from the normal), so its radiance is a E / pi = a L_e (r / D)^2 cos theta_c. Nothing else
// reaches it: the object is a black absorber (eta = 1, albedo 0) behind the camera, where it
// blocks no shadow ray, and light from the floor's bounce that goes straight to the light is
// next-event estimation's (counted twice, the pixel would be too bright). Tolerance 4 sigma.
TEST(RenderVolumetric, FloorUnderSphereLightFollowsLambert) {
  const double radiance = 2.0, albedo = 0.7, height = -1.0;
  RenderScene scene = sphere_scene(50.0, 0.0, 0.0, 1.0, radiance, 12, 24);
  for (Vec3& p : scene.mesh.positions) p = 0.5 * p + Vec3(0.0, -9.0, 0.0);
  scene.light.position = Vec3(0.0, 0.0, 3.0);
  scene.light.radius = 0.6;
  scene.light.intensity = radiance * pi * 0.6 * 0.6;
  scene.camera.position = Vec3(0.0, -4.0, 1.0);
  scene.camera.look_at = Vec3(0.0, 0.0, -1.0);
  scene.floor = RenderFloor{height, {albedo, albedo, albedo}};
  scene.width = 8;
  scene.height = 8;
  scene.samples = 4000;
  scene.validate();
  const VolumetricResult result = render_volumetric(scene, volumetric(12));
  for (int j = 0; j < scene.height; ++j) {
    for (int i = 0; i < scene.width; ++i) {
      const Vec3 d = scene.camera.ray_direction(i, j, scene.width, scene.height);
      ASSERT_LT(d.z(), 0.0);
      const Vec3 x = scene.camera.position + (height - scene.camera.position.z()) / d.z() * d;
      const Vec3 to_light = scene.light.position - x;
      const double dist = to_light.norm();
      const double expected =
          albedo * radiance * std::pow(scene.light.radius / dist, 2) * to_light.z() / dist;
      const double se = result.standard_error.channels[0].at(i, j);
      EXPECT_GT(se, 0.0);
      EXPECT_NEAR(result.image.channels[0].at(i, j), expected, 4.0 * se)
          << "pixel " << i << ", " << j;
    }
  }
}

// The once-scattered part (scattering_order = 1) equals the single-scatter path tracer where the
// two estimate the same integral: eta = 1 (pathtrace leaves out the paths that reflect inside),
// no floor, a black environment. Whole image within 4 sigma of the two errors combined, and the
// mean z^2 over lit pixels near 1.
TEST(RenderVolumetric, OnceScatteredPartMatchesPathtrace) {
  RenderScene scene = sphere_scene(0.1, 0.6, 0.3, 1.0, 1.0, 24, 48);
  scene.light.position = Vec3(0.0, 1.2, 2.4);
  scene.light.radius = 0.7;
  scene.light.intensity = 1.0;
  scene.width = 6;
  scene.height = 6;
  scene.samples = 100000;
  scene.validate();
  RenderSettings traced;
  traced.method = RenderMethod::pathtrace;
  traced.seed = 3;
  const RenderResult reference = render_single_scatter(scene, traced);
  RenderSettings once = volumetric(4);
  once.scattering_order = 1;
  const VolumetricResult result = render_volumetric(scene, once);
  double sum_v = 0.0, sum_p = 0.0, var = 0.0, z2 = 0.0;
  int lit = 0;
  for (std::size_t k = 0; k < reference.image.values.size(); ++k) {
    const double v = result.image.channels[0].values[k], p = reference.image.values[k];
    const double se_v = result.standard_error.channels[0].values[k];
    const double se_p = reference.standard_error.values[k];
    sum_v += v;
    sum_p += p;
    var += se_v * se_v + se_p * se_p;
    if (se_v > 0.0 && se_p > 0.0) {
      z2 += (v - p) * (v - p) / (se_v * se_v + se_p * se_p);
      ++lit;
    }
  }
  ASSERT_GT(lit, 12);
  ASSERT_GT(sum_p, 0.0);
  const double sigma = std::sqrt(var);
  EXPECT_LT(sigma, 0.05 * sum_p);  // the comparison has teeth
  EXPECT_NEAR(sum_v, sum_p, 4.0 * sigma);
  // Mean of `lit` squared z-scores: 1 on average; 2 is far beyond its spread for 12+ pixels.
  EXPECT_LT(z2 / lit, 2.0);
}

// Every order against the once-scattered part: more light, never less.
TEST(RenderVolumetric, HigherOrdersAddLight) {
  RenderScene scene = sphere_scene(0.05, 1.5, 0.0, 1.3, 1.0, 16, 32);
  scene.floor = RenderFloor{-1.5, {0.8, 0.8, 0.8}};
  scene.samples = 400;
  scene.validate();
  const VolumetricResult all = render_volumetric(scene, volumetric(8));
  RenderSettings once = volumetric(8);
  once.scattering_order = 1;
  const VolumetricResult first = render_volumetric(scene, once);
  double a = 0.0, b = 0.0;
  for (std::size_t k = 0; k < all.image.channels[0].values.size(); ++k) {
    a += all.image.channels[0].values[k];
    b += first.image.channels[0].values[k];
  }
  EXPECT_GT(a, b);
  EXPECT_GT(all.counters.shadow_rays, 0u);
}

// A medium per channel renders three channels: an absorbing red channel comes out darker than
// the other two, which are the same medium and the same paths.
TEST(RenderVolumetric, ChannelsFollowTheirMedia) {
  RenderScene scene = sphere_scene(0.0, 2.0, 0.0, 1.3, 1.0, 16, 32);
  scene.environment_radiance = 1.0;
  scene.channel_media = {Medium::from_coefficients(1.0, 1.0, 0.0, "mesh units"),
                         Medium::from_coefficients(0.0, 2.0, 0.0, "mesh units"),
                         Medium::from_coefficients(0.0, 2.0, 0.0, "mesh units")};
  scene.validate();
  const VolumetricResult result = render_volumetric(scene, volumetric(2));
  double red = 0.0, green = 0.0, blue = 0.0;
  for (std::size_t k = 0; k < result.image.channels[0].values.size(); ++k) {
    red += result.image.channels[0].values[k];
    green += result.image.channels[1].values[k];
    blue += result.image.channels[2].values[k];
  }
  EXPECT_LT(red, 0.9 * green);
  EXPECT_NEAR(green, blue, 1e-9 * green);  // albedo 1 in both: every path returns L_e
}

// The furnace in colour: three media of albedo 1 with different sigma_t and g share one path,
// whose channel weights are ratios of densities (not 1), so each channel equals L_e only on
// average: every pixel within 4 sigma, and each channel's image mean within 4 sigma of it.
TEST(RenderVolumetric, WhiteFurnaceInColour) {
  const double radiance = 1.5;
  RenderScene scene = sphere_scene(0.0, 1.0, 0.0, 1.4, radiance, 16, 32);
  scene.environment_radiance = radiance;
  scene.channel_media = {Medium::from_coefficients(0.0, 0.7, 0.0, "mesh units"),
                         Medium::from_coefficients(0.0, 2.0, 0.5, "mesh units"),
                         Medium::from_coefficients(0.0, 4.0, 0.8, "mesh units")};
  scene.medium = scene.channel_media[1];
  scene.samples = 3000;
  scene.validate();
  const VolumetricResult result = render_volumetric(scene, volumetric(13));
  for (int c = 0; c < 3; ++c) {
    double sum = 0.0, var = 0.0, spread = 0.0;
    const auto& values = result.image.channels[c].values;
    for (std::size_t k = 0; k < values.size(); ++k) {
      const double se = result.standard_error.channels[c].values[k];
      EXPECT_NEAR(values[k], radiance, 4.0 * se + 1e-12) << "channel " << c << ", pixel " << k;
      sum += values[k];
      var += se * se;
      spread = std::max(spread, se);
    }
    EXPECT_GT(spread, 0.0) << "channel " << c;  // the weights did vary
    EXPECT_NEAR(sum, radiance * static_cast<double>(values.size()), 4.0 * std::sqrt(var));
  }
}

// One path for three media equals three renders of one medium each: per channel, the image sum
// within 4 sigma (both errors combined) and the mean z^2 over pixels below 2. Absorbing media of
// different sigma_t and g, a coloured floor, the sphere light and an environment.
TEST(RenderVolumetric, ChannelsMatchSeparateRenders) {
  RenderScene scene = sphere_scene(0.0, 1.0, 0.0, 1.3, 1.0, 16, 32);
  const std::vector<Medium> media = {Medium::from_coefficients(0.02, 0.8, 0.0, "mesh units"),
                                     Medium::from_coefficients(0.2, 1.6, 0.4, "mesh units"),
                                     Medium::from_coefficients(0.6, 3.0, 0.7, "mesh units")};
  const std::array<double, 3> floor_albedo = {0.8, 0.5, 0.3};
  scene.light.radius = 0.8;
  scene.light.intensity = 1.0;
  scene.channel_media = media;
  scene.medium = media[1];
  scene.floor = RenderFloor{-1.2, floor_albedo};
  scene.environment_radiance = 0.5;
  scene.samples = 4000;
  scene.validate();
  const VolumetricResult colour = render_volumetric(scene, volumetric(21));
  for (std::size_t c = 0; c < 3; ++c) {
    RenderScene single = scene;
    single.channel_media.clear();
    single.medium = media[c];
    single.floor = RenderFloor{-1.2, {floor_albedo[c], floor_albedo[c], floor_albedo[c]}};
    const VolumetricResult one = render_volumetric(single, volumetric(22));
    double a = 0.0, b = 0.0, var = 0.0, z2 = 0.0;
    int counted = 0;
    for (std::size_t k = 0; k < one.image.channels[0].values.size(); ++k) {
      const double x = colour.image.channels[c].values[k], y = one.image.channels[0].values[k];
      const double v = std::pow(colour.standard_error.channels[c].values[k], 2) +
                       std::pow(one.standard_error.channels[0].values[k], 2);
      a += x;
      b += y;
      var += v;
      if (v > 0.0) {
        z2 += (x - y) * (x - y) / v;
        ++counted;
      }
    }
    ASSERT_GT(counted, 20);
    EXPECT_LT(std::sqrt(var), 0.01 * b);  // the comparison has teeth
    EXPECT_NEAR(a, b, 4.0 * std::sqrt(var)) << "channel " << c;
    EXPECT_LT(z2 / counted, 2.0) << "channel " << c;
  }
}

// The same image for any thread count: streams keyed by (seed, pixel, sample).
TEST(RenderVolumetric, ImageIndependentOfThreads) {
  RenderScene scene = sphere_scene(0.05, 1.5, 0.3, 1.3, 1.0, 16, 32);
  scene.floor = RenderFloor{-1.2, {0.5, 0.5, 0.5}};
  scene.samples = 30;
  scene.validate();
  RenderSettings one = volumetric(9), two = volumetric(9);
  one.threads = 1;
  two.threads = 2;
  const VolumetricResult a = render_volumetric(scene, one);
  const VolumetricResult b = render_volumetric(scene, two);
  EXPECT_EQ(a.image.channels[1].values, b.image.channels[1].values);
}

TEST(RenderVolumetric, BadScenesNameTheirKey) {
  const std::string sphere = "[mesh]\nshape = \"sphere\"\n";
  const std::string light = "[light]\nposition = [0, 0, 4]\nradius = 0.2\n";
  EXPECT_EQ(field_of([&] {
              parse_render_scene(sphere + light + "[camera]\nposition = [0.1, 0.2, 0.0]\n",
                                 "t.toml");
            }),
            "camera.position");
  EXPECT_EQ(
      field_of([&] { parse_render_scene(sphere + light + "[floor]\nheight = -0.5\n", "t.toml"); }),
      "floor.height");
  EXPECT_EQ(field_of([&] {
              parse_render_scene(sphere + light + "[floor]\nheight = -2\nalbedo = 1.2\n", "t.toml");
            }),
            "floor.albedo");
  EXPECT_EQ(field_of([&] {
              parse_render_scene(sphere + light + "[medium]\nsigma_s = [1, 2]\n", "t.toml");
            }),
            "medium.sigma_s");
  EXPECT_EQ(field_of([&] {
              parse_render_scene(
                  sphere + light + "[medium]\nmaterial = \"wholemilk\"\nsigma_a = 0.1\n", "t.toml");
            }),
            "medium.sigma_a");
  EXPECT_EQ(field_of([&] {
              parse_render_scene(sphere + light + "[medium]\nmaterial = \"wholemlik\"\n", "t.toml");
            }),
            "medium.material");
  for (const auto& [line, field] :
       {std::pair{"radiance = -1", "environment.radiance"},
        std::pair{"radiance = nan", "environment.radiance"}, std::pair{"L = 1", "environment.L"}}) {
    const std::string text = sphere + light + "[environment]\n" + line + "\n";
    EXPECT_EQ(field_of([&] { parse_render_scene(text, "t.toml"); }), field) << line;
  }
  // Per-channel media, floors and environments are for volumetric only; volumetric needs a
  // sphere light.
  const RenderScene lit =
      parse_render_scene(sphere + light + "[environment]\nradiance = 0.25\n", "t.toml");
  EXPECT_EQ(lit.environment_radiance, 0.25);
  const RenderScene coloured = parse_render_scene(
      sphere + light + "[medium]\nmaterial = \"wholemilk\"\nlength_unit = \"mm\"\n", "t.toml");
  ASSERT_EQ(coloured.channel_media.size(), 3u);
  EXPECT_GT(coloured.channel_media[2].sigma_t, coloured.channel_media[0].sigma_t);
  EXPECT_DOUBLE_EQ(coloured.eta, 1.3);  // the table's
  RenderSettings holzschuch;
  holzschuch.method = RenderMethod::holzschuch;
  EXPECT_EQ(field_of([&] { render_single_scatter(coloured, holzschuch); }), "medium");
  EXPECT_EQ(field_of([&] { render_single_scatter(lit, holzschuch); }), "environment");
  RenderScene point = parse_render_scene(sphere, "t.toml");
  EXPECT_EQ(field_of([&] { render_volumetric(point, volumetric(1)); }), "light.radius");
}

}  // namespace
}  // namespace scatterlab
