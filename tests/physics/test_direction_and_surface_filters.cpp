// Declared tallies binned by the direction of travel and by where light leaves a sphere or a mesh
// (transport/declared_tally.hpp), held against exact results and against the geometries' own
// tallies, which score the same events. Fixed seeds; tolerances k sigma.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/mesh/lit_mesh.hpp"
#include "scatterlab/transport/lit_object.hpp"
#include "scatterlab/transport/searchlight.hpp"
#include "simulation_fixtures.hpp"

namespace scatterlab {
namespace {

using testing::find_tally;
using testing::scalar;

DeclaredFilter bins(Coordinate coordinate, int count) {
  return {coordinate, {}, {}, count};
}

DeclaredFilter axis(Coordinate coordinate, double min, double max, int count) {
  return {coordinate, min, max, count};
}

// An infinite medium's beam with none of its own volume tallies, for declared ones: 20 batches.
InfiniteMediumSpec declared_only(const Medium& medium, std::uint64_t photons, std::uint64_t seed) {
  InfiniteMediumSpec spec;
  spec.medium = medium;
  spec.tallies.radiance = spec.tallies.fluence = spec.tallies.flux = false;
  spec.run.photons = photons;
  spec.run.batches = 20;
  spec.run.seed = seed;
  return spec;
}

// P(cos theta <= x) of the Henyey-Greenstein phase function with mean cosine g.
double henyey_greenstein_cdf(double x, double g) {
  return (1.0 - g * g) / (2.0 * g) * (1.0 / std::sqrt(1.0 + g * g - 2.0 * g * x) - 1.0 / (1.0 + g));
}

// A pencil beam along +z in an infinite medium: every photon collides once unscattered, and with
// probability albedo once more after one scattering, travelling along a direction drawn from the
// phase function about +z, at an azimuth drawn uniformly. So the once-scattered collisions of a
// fluence binned by (theta, phi) are exactly albedo P_HG(band) / phi bins per photon, and each
// cell, per steradian, that over its solid angle (cos theta0 - cos theta1) (phi1 - phi0).
TEST(DirectionFilters, OnceScatteredCollisionsFollowThePhaseFunction) {
  InfiniteMediumSpec spec = declared_only(Medium::from_albedo(0.9, 1.0, 0.7, "mfp"), 200'000, 5);
  const int theta_bins = 12, phi_bins = 4;
  spec.declared_tallies = {{"by_direction",
                            Score::fluence,
                            {bins(Coordinate::theta, theta_bins), bins(Coordinate::phi, phi_bins),
                             bins(Coordinate::order, 3)},
                            std::nullopt},
                           {"in_all", Score::fluence, {}, std::nullopt}};
  const TransportOutput out = run_infinite_medium(spec);
  const TallyResult& d = find_tally(out, "by_direction");
  ASSERT_EQ(d.dims, (std::vector<std::string>{"theta", "phi", "order"}));
  EXPECT_EQ(d.units, "W mfp sr^-1 per W incident");
  const UniformAxis theta{0.0, pi, theta_bins};
  const double width = 2.0 * pi / phi_bins;
  double total = 0.0;
  for (int k = 0; k < theta_bins; ++k) {
    const double c0 = std::cos(theta.edge(k)), c1 = std::cos(theta.edge(k + 1));
    const double share =
        henyey_greenstein_cdf(c0, spec.medium.g) - henyey_greenstein_cdf(c1, spec.medium.g);
    const double exact = spec.medium.albedo * share / phi_bins / ((c0 - c1) * width);
    for (int j = 0; j < phi_bins; ++j) {
      const std::size_t cell = (static_cast<std::size_t>(k) * phi_bins + j) * 3;
      EXPECT_NEAR(d.mean[cell + 1], exact, 4.0 * d.stderr_of_mean[cell + 1] + 1e-12)
          << "theta bin " << k << ", phi bin " << j;
      for (int order = 0; order < 3; ++order) total += d.mean[cell + order] * (c0 - c1) * width;
    }
  }
  // Unscattered, every photon collides once along +z: theta bin 0, phi 0 (on the axis).
  EXPECT_NEAR(d.mean[0] * (1.0 - std::cos(theta.edge(1))) * width, 1.0, 1e-12);
  // The same collisions as the tally without filters, to round-off; and that is the mean number
  // of collisions (1 mfp each), 1 / (1 - albedo).
  const TallyResult& all = find_tally(out, "in_all");
  EXPECT_NEAR(total, all.mean[0], 1e-12 * all.mean[0]);
  EXPECT_NEAR(all.mean[0], 1.0 / (1.0 - spec.medium.albedo), 4.0 * all.stderr_of_mean[0]);
}

// At normal incidence a half-space is symmetric about its normal: the light leaving it is
// spread evenly in azimuth, at every exit angle. The azimuth bins of (theta_o, phi), each a solid
// angle, add up to the exit-angle tally of the same run to round-off.
TEST(DirectionFilters, ExitAzimuthOfAPlaneAddsUpToItsExitAngles) {
  HalfSpaceSpec spec;
  spec.medium = Medium::from_albedo(0.95, 1.0, 0.5, "mfp");
  spec.eta = 1.4;
  spec.run.photons = 100'000;
  spec.run.batches = 20;
  spec.run.seed = 9;
  const int phi_bins = 6;
  spec.declared_tallies = {
      {"angles", Score::exitance, {bins(Coordinate::exit_angle, 5)}, std::nullopt},
      {"angles_azimuths",
       Score::exitance,
       {bins(Coordinate::exit_angle, 5), bins(Coordinate::phi, phi_bins)},
       std::nullopt}};
  const TransportOutput out = run_half_space(spec);
  const TallyResult& one = find_tally(out, "angles");
  const TallyResult& two = find_tally(out, "angles_azimuths");
  EXPECT_EQ(two.units, "W sr^-1 per W incident");
  const double width = 2.0 * pi / phi_bins;
  for (std::size_t k = 0; k < 5; ++k) {
    double sum = 0.0;
    for (std::size_t j = 0; j < phi_bins; ++j) {
      const std::size_t cell = k * phi_bins + j;
      sum += two.mean[cell] * width;
      EXPECT_NEAR(two.mean[cell], one.mean[k],
                  4.0 * std::hypot(two.stderr_of_mean[cell], one.stderr_of_mean[k]))
          << "theta_o bin " << k << ", phi bin " << j;
    }
    EXPECT_NEAR(sum, 2.0 * pi * one.mean[k], 1e-12 * one.mean[k]) << "theta_o bin " << k;
  }
}

// The sphere's own exitance (psi, azimuth) and a declared one bin the same exits by the same
// patches: equal to round-off. psi alone is the sum over azimuths.
TEST(SurfaceFilters, SpherePatchesAreTheSpheresOwnExitance) {
  LitObjectSpec spec;
  spec.medium = Medium::from_albedo(0.9, 1.0, 0.3, "mfp");
  spec.eta = 1.3;
  spec.light = ObjectLight::beam;
  spec.beam_origin = {0.3, 0.2, -2.0};
  spec.psi = {0.0, pi, 6};
  spec.azimuth = {0.0, 2.0 * pi, 4};
  spec.run.photons = 50'000;
  spec.run.batches = 10;
  spec.run.seed = 2;
  spec.declared_tallies = {{"patches",
                            Score::exitance,
                            {bins(Coordinate::psi, 6), bins(Coordinate::azimuth, 4)},
                            std::nullopt},
                           {"bands", Score::exitance, {bins(Coordinate::psi, 6)}, std::nullopt}};
  const TransportOutput out = run_lit_sphere(spec);
  const TallyResult& own = find_tally(out, "exitance");
  const TallyResult& patches = find_tally(out, "patches");
  const TallyResult& bands = find_tally(out, "bands");
  ASSERT_EQ(patches.size(), own.size());
  EXPECT_EQ(patches.units, own.units);
  for (std::size_t i = 0; i < own.size(); ++i) {
    EXPECT_NEAR(patches.mean[i], own.mean[i], 1e-12 * own.mean[i]) << "patch " << i;
  }
  for (std::size_t k = 0; k < 6; ++k) {
    double sum = 0.0;
    for (std::size_t j = 0; j < 4; ++j) sum += own.mean[k * 4 + j] / 4.0;
    EXPECT_NEAR(bands.mean[k], sum, 1e-12 * sum) << "band " << k;
  }
}

// A pole beam crosses a sphere of radius R along its axis: the light that does not scatter
// leaves at the antipode (psi = pi, the last band) after 2 R n / c. Of the power
// incident, (1 - F) enters and (1 - F) of what reaches the far side leaves, F the Fresnel
// reflectance at normal incidence: (1 - F)^2 exp(-2 sigma_t R).
TEST(SurfaceFilters, UnscatteredLightLeavesTheSphereAtTheAntipodeOnTime) {
  LitObjectSpec spec;
  spec.medium = Medium::from_albedo(0.8, 2.0, 0.5, "mm");
  spec.radius = 0.5;  // mm: 2 mfp across
  spec.eta = 1.4;
  spec.light = ObjectLight::pole_beam;
  spec.run.photons = 100'000;
  spec.run.batches = 10;
  spec.run.seed = 4;
  const double arrival = 2.0 * spec.radius * 1.4 * 1e-3 / speed_of_light;  // s
  spec.declared_tallies = {{"on_time",
                            Score::exitance,
                            {bins(Coordinate::psi, 4),
                             axis(Coordinate::t, arrival * (1.0 - 1e-9), arrival * (1.0 + 1e-9), 1),
                             bins(Coordinate::order, 2)},
                            std::nullopt},
                           {"exits",
                            Score::exitance,
                            {bins(Coordinate::psi, 4), bins(Coordinate::order, 2)},
                            std::nullopt},
                           {"paths",
                            Score::path_length,
                            {bins(Coordinate::psi, 4), bins(Coordinate::order, 2)},
                            std::nullopt}};
  const TransportOutput out = run_lit_sphere(spec);
  const TallyResult& t = find_tally(out, "on_time");
  ASSERT_EQ(t.dims, (std::vector<std::string>{"psi", "t", "order"}));
  EXPECT_EQ(t.units, "W mm^-2 per J incident");
  // Cells (psi, order): the unscattered light in the last band, cell 6. Nothing else, unscattered
  // or not: scattered light leaves with a path of exactly 2 R with probability 0.
  const std::size_t antipode = 3 * 2 + 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (i != antipode) {
      EXPECT_EQ(t.mean[i], 0.0) << "cell " << i;
    }
  }
  const double band = 2.0 * pi * spec.radius * spec.radius * (1.0 - std::cos(0.25 * pi));
  const double width = 2e-9 * arrival;
  const double f = fresnel_dielectric_reflectance(1.0, 1.4);
  const double exact = (1.0 - f) * (1.0 - f) * std::exp(-2.0 * 2.0 * spec.radius);
  EXPECT_NEAR(t.mean[antipode] * band * width, exact,
              4.0 * t.stderr_of_mean[antipode] * band * width);
  // The path of each unscattered photon leaving there is the diameter, 2R: the path-weighted
  // exitance is 2R times the exitance, to round-off.
  const TallyResult& paths = find_tally(out, "paths");
  const TallyResult& exits = find_tally(out, "exits");
  EXPECT_EQ(paths.units, "W mm^-1 per W incident");
  EXPECT_NEAR(paths.mean[antipode], 2.0 * spec.radius * exits.mean[antipode],
              1e-9 * paths.mean[antipode]);
  EXPECT_GT(exits.mean[antipode], 0.0);
}

// In an infinite medium every photon collides a geometric number of times, mean 1 / (1 -
// albedo), whatever g; the fluence's collision estimator scores each 1 mfp, 1 / sigma_t in mm.
TEST(Scores, CollisionsCountWhatTheFluenceWeighsByAMeanFreePath) {
  InfiniteMediumSpec spec = declared_only(Medium::from_albedo(0.9, 2.0, 0.6, "mm"), 50'000, 6);
  spec.declared_tallies = {{"collisions", Score::collisions, {}, std::nullopt},
                           {"fluence_in_all", Score::fluence, {}, std::nullopt}};
  const TransportOutput out = run_infinite_medium(spec);
  const TallyResult& n = find_tally(out, "collisions");
  const TallyResult& phi = find_tally(out, "fluence_in_all");
  EXPECT_EQ(n.units, "W per W incident");
  EXPECT_EQ(phi.units, "W mm per W incident");
  EXPECT_NEAR(n.mean[0], 1.0 / (1.0 - 0.9), 4.0 * n.stderr_of_mean[0]);
  EXPECT_NEAR(phi.mean[0], n.mean[0] / 2.0, 1e-12 * phi.mean[0]);
}

LitObjectSpec lit_box(TriangleMesh mesh) {
  LitObjectSpec spec;
  spec.mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
  spec.mesh_source = "test";
  spec.medium = Medium::from_albedo(0.7, 1.5, 0.0, "mm");
  spec.eta = 1.5;
  spec.light = ObjectLight::beam;
  spec.beam_origin = {0.1, 0.2, -3.0};
  spec.run.photons = 100'000;
  spec.run.batches = 10;
  spec.run.seed = 8;
  return spec;
}

// A beam through a box 2 mm deep, normal to its faces: no light leaves the far face (+z,
// triangles 2 and 3 of make_box) before 2 mm x n / c, unscattered light leaves then,
// (1 - F)^2 exp(-2 sigma_t) of it, and a declared exitance per triangle is the mesh's own.
TEST(SurfaceFilters, TimeAndTrianglesOnAConvexMesh) {
  LitObjectSpec spec = lit_box(make_box(Vec3(1.0, 1.0, 1.0)));
  const double arrival = 2.0 * 1.5 * 1e-3 / speed_of_light;  // s
  spec.declared_tallies = {
      {"triangles", Score::exitance, {{Coordinate::triangle, {}, {}, 0}}, std::nullopt},
      {"early",
       Score::exitance,
       {{Coordinate::triangle, {}, {}, 0}, axis(Coordinate::t, 0.0, arrival * (1.0 - 1e-9), 1)},
       std::nullopt},
      {"on_time",
       Score::exitance,
       {axis(Coordinate::t, arrival * (1.0 - 1e-9), arrival * (1.0 + 1e-9), 1),
        bins(Coordinate::order, 2)},
       std::nullopt}};
  const TransportOutput out = run_lit_mesh(spec);
  const TallyResult& own = find_tally(out, "exitance");
  const TallyResult& triangles = find_tally(out, "triangles");
  ASSERT_EQ(triangles.size(), own.size());
  EXPECT_EQ(triangles.units, own.units);
  for (std::size_t i = 0; i < own.size(); ++i) {
    EXPECT_NEAR(triangles.mean[i], own.mean[i], 1e-12 * own.mean[i]) << "triangle " << i;
  }
  const TallyResult& early = find_tally(out, "early");
  EXPECT_EQ(early.mean.at(2), 0.0);
  EXPECT_EQ(early.mean.at(3), 0.0);
  EXPECT_GT(early.mean.at(0) + early.mean.at(1), 0.0);  // the lit face (-z) has early light
  const TallyResult& t = find_tally(out, "on_time");
  EXPECT_EQ(t.mean.at(1), 0.0);
  const double width = 2e-9 * arrival;
  const double f = fresnel_dielectric_reflectance(1.0, 1.5);
  const double exact = (1.0 - f) * (1.0 - f) * std::exp(-2.0 * 1.5);
  EXPECT_NEAR(t.mean.at(0) * width, exact, 4.0 * t.stderr_of_mean.at(0) * width);
}

// Light that leaves a mesh that is not convex may enter it again across air the walk does not
// time: a time filter there is refused by name, before any photon runs.
TEST(SurfaceFilters, TimeOnAMeshThatIsNotConvexIsRefused) {
  TriangleMesh two = make_box(Vec3(1.0, 1.0, 0.5));
  append_mesh(two, make_box(Vec3(1.0, 1.0, 0.5)), Vec3(0.0, 0.0, 2.0));
  LitObjectSpec spec = lit_box(std::move(two));
  spec.declared_tallies = {
      {"late", Score::exitance, {axis(Coordinate::t, 0.0, 1e-10, 4)}, std::nullopt}};
  try {
    run_lit_mesh(spec);
    FAIL() << "time on two boxes accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "tally[1].filters.t");
  }
}

}  // namespace
}  // namespace scatterlab
