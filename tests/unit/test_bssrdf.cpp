// The diffusion BSSRDF on surfaces: the profile sampler is unbiased, the BSSRDF's exitance is its
// profile (Bitterli eq. 2.16's normalisation), and the lit sphere's Monte Carlo integral
// (models/lit_sphere_exitance.hpp) converges to an independent nested quadrature of the same
// double integral and, on a very large sphere, to the half-space's R_dr at the lit pole.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "input_error_field.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/quadrature.hpp"
#include "scatterlab/core/random.hpp"
#include "scatterlab/models/bssrdf.hpp"
#include "scatterlab/models/diffusion_profile.hpp"
#include "scatterlab/models/lit_sphere_exitance.hpp"

namespace scatterlab {
namespace {

using test_support::field_of;
constexpr double pi = std::numbers::pi;

HalfSpaceMedium medium(double albedo, double eta) {
  return HalfSpaceMedium::from_albedo(albedo, 0.0, eta);
}

TEST(RadialProfileSampler, ItsWeightsAreAnUnbiasedEstimateOfTheProfilesIntegral) {
  for (const ProfileModel model : all_profile_models) {
    const DiffusionProfile profile(model, medium(0.9, 1.3));
    const RadialProfileSampler sampler(profile, 1e3);
    // Out to 1000 mfp the profile (decaying as exp(-sigma_tr r), sigma_tr ~ 0.5) is all there.
    EXPECT_NEAR(sampler.integral() / profile.total_reflectance(), 1.0, 1e-9) << to_string(model);
    PhotonRandom random(7, 0);
    const int n = 100'000;
    double sum = 0.0, sum_sq = 0.0;
    for (int i = 0; i < n; ++i) {
      double density = 0.0;
      const double r = sampler.sample(random.next(), density);
      ASSERT_NEAR(density, sampler.density(r), 1e-12 * density);
      const double w = 2.0 * pi * r * profile.reflectance(r) / density;
      sum += w;
      sum_sq += w * w;
    }
    const double mean = sum / n;
    const double sigma = std::sqrt((sum_sq / n - mean * mean) / n);
    EXPECT_LT(std::abs(mean - sampler.integral()), 4.0 * sigma) << to_string(model);
    EXPECT_LT(sigma, 0.01 * mean) << to_string(model);  // the draw follows the profile
  }
}

TEST(Bssrdf, ItsExitanceIsTheProfileTimesTheNormalisationsFit) {
  const GaussLegendre rule = gauss_legendre(64);
  for (const double eta : {0.7, 1.0, 1.3, 2.0}) {
    const DiffusionProfile profile(ProfileModel::better_dipole, medium(0.9, eta));
    const double ratio = exit_transmittance_ratio(eta);
    // d'Eon & Irving's C_1 fit is within 0.006 of the quadrature (boundary_reflection.hpp).
    EXPECT_NEAR(ratio, 1.0, 0.006) << eta;
    // int S cos(theta_o) dw_o over the hemisphere, for normal entry at r = 1: by Gauss-Legendre
    // in mu_o on each side of the kink (total reflection from outside for eta < 1).
    const double kink = eta < 1.0 ? std::sqrt(1.0 - eta * eta) : 0.0;
    double exitance = 0.0;
    for (const auto& [a, b] : {std::pair{0.0, kink}, std::pair{kink, 1.0}}) {
      for (std::size_t k = 0; k < rule.nodes.size(); ++k) {
        const double mu = a + 0.5 * (b - a) * (rule.nodes[k] + 1.0);
        exitance += 0.5 * (b - a) * rule.weights[k] * 2.0 * pi * mu * bssrdf(profile, 1.0, 1.0, mu);
      }
    }
    const double expected =
        fresnel_dielectric_transmittance(1.0, eta) * profile.reflectance(1.0) * ratio;
    // F_t has a square-root edge at the kink, which Gauss-Legendre resolves to ~1e-6.
    EXPECT_NEAR(exitance / expected, 1.0, 1e-5) << eta;
  }
}

TEST(LitSphereExitance, ConvergesToTheDoubleIntegral) {
  const double radius = 2.0;  // a coarse sphere: 2 mfp
  const std::vector<double> edges{0.0, pi / 4.0, pi / 2.0, 3.0 * pi / 4.0, pi};
  for (const ProfileModel model : {ProfileModel::dipole, ProfileModel::better_dipole}) {
    const DiffusionProfile profile(model, medium(0.9, 1.3));
    const LitSphereExitance mc = lit_sphere_exitance(profile, radius, edges, 40'000, 3);
    for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
      const double exact = lit_sphere_exitance_quadrature(profile, radius, edges[b], edges[b + 1]);
      EXPECT_LT(std::abs(mc.mean[b] - exact), 4.0 * mc.stderr_of_mean[b])
          << to_string(model) << " bin " << b << ": " << mc.mean[b] << " +- "
          << mc.stderr_of_mean[b] << " against " << exact;
      EXPECT_LT(mc.stderr_of_mean[b], 0.01 * exact) << to_string(model) << " bin " << b;
    }
  }
}

TEST(LitSphereExitance, AtTheLitPoleOfAVeryLargeSphereIsTheHalfSpace) {
  // R = 1000 mfp: over the profile's reach (tens of mfp) the surface is flat and lit at normal
  // incidence, so M pi R^2 -> F_t(1) R_dr (the exitance of S_d per unit R_d included).
  const double radius = 1000.0;
  const DiffusionProfile profile(ProfileModel::quantized_diffusion, medium(0.95, 1.3));
  const std::vector<double> edges{0.0, 0.01};
  const LitSphereExitance mc = lit_sphere_exitance(profile, radius, edges, 20'000, 5);
  const double flat = fresnel_dielectric_transmittance(1.0, 1.3) * profile.total_reflectance() *
                      exit_transmittance_ratio(1.3);
  const double scale = pi * radius * radius;
  EXPECT_LT(std::abs(mc.mean[0] * scale - flat), 4.0 * mc.stderr_of_mean[0] * scale + 1e-3 * flat)
      << mc.mean[0] * scale << " +- " << mc.stderr_of_mean[0] * scale << " against " << flat;
}

TEST(LitSphereExitance, ItsPowerIsThePowerEnteredTimesTheProfilesTotal) {
  // Energy: on a sphere the area at chord d from any point is the plane's (d dd dbeta), so the
  // power a BSSRDF sends out of the whole sphere is the power that entered times R_d integrated
  // over [0, 2R], times the exit factor. The power entering per unit power meeting the sphere is
  // 2 int_0^1 F_t(mu) mu dmu: the shadow disc seen at angle theta_i has cos(theta_i) dA.
  const double radius = 3.0, eta = 1.3;
  const DiffusionProfile profile(ProfileModel::better_dipole, medium(0.8, eta));
  std::vector<double> edges;
  for (int i = 0; i <= 18; ++i) edges.push_back(pi * i / 18.0);
  const LitSphereExitance mc = lit_sphere_exitance(profile, radius, edges, 20'000, 11);
  double power = 0.0, variance = 0.0;
  for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
    const double area = 2.0 * pi * radius * radius * (std::cos(edges[b]) - std::cos(edges[b + 1]));
    power += mc.mean[b] * area;
    variance += std::pow(mc.stderr_of_mean[b] * area, 2);
  }
  const double entered =
      integrate_adaptive(
          [&](double mu) { return 2.0 * fresnel_dielectric_transmittance(mu, eta) * mu; }, 0.0, 1.0)
          .value;
  const double within = profile.total_reflectance() -
                        profile.annulus_averages(std::vector<double>{2.0 * radius, 1e4})[0] * pi *
                            (1e8 - 4.0 * radius * radius);
  const double expected = entered * within * exit_transmittance_ratio(eta);
  EXPECT_LT(std::abs(power - expected), 4.0 * std::sqrt(variance))
      << power << " against " << expected;
  EXPECT_LT(std::sqrt(variance), 0.003 * expected);
}

TEST(MeasuredProfile, OnFineRingsOfAModelGivesTheModelsLitSphere) {
  // A measured profile holding the better dipole's exact ring averages on 0.02-mfp rings: its
  // annulus averages and total are the rings' own, and on the lit sphere it gives what the
  // model gives (the same samples: the difference is the rings' discretisation alone).
  const HalfSpaceMedium m = medium(0.9, 1.3);
  const DiffusionProfile model(ProfileModel::better_dipole, m);
  const double radius = 2.0;
  RingProfile rings;
  for (int i = 0; i <= 200; ++i) rings.r_edges.push_back(0.02 * i);
  rings.mean = model.annulus_averages(rings.r_edges);
  rings.stderr_of_mean.assign(rings.mean.size(), 0.0);
  const DiffusionProfile measured(rings, m);
  EXPECT_EQ(measured.model(), ProfileModel::measured);
  const std::vector<double> back = measured.annulus_averages(rings.r_edges);
  for (std::size_t i = 0; i < back.size(); ++i)
    EXPECT_NEAR(back[i], rings.mean[i], 1e-12 * rings.mean[i]);
  // Its total is the model's light within the last ring, in closed form.
  const double within =
      model.total_reflectance() -
      model.annulus_averages(std::vector<double>{4.0, 1e4})[0] * pi * (1e8 - 16.0);
  EXPECT_NEAR(measured.total_reflectance() / within, 1.0, 1e-9);
  const std::vector<double> edges{0.0, pi / 3.0, 2.0 * pi / 3.0, pi};
  const LitSphereExitance a = lit_sphere_exitance(model, radius, edges, 20'000, 9);
  const LitSphereExitance b = lit_sphere_exitance(measured, radius, edges, 20'000, 9);
  for (std::size_t k = 0; k < a.mean.size(); ++k) {
    EXPECT_NEAR(b.mean[k] / a.mean[k], 1.0, 0.01) << k;
    EXPECT_NEAR(b.stderr_of_mean[k] / a.stderr_of_mean[k], 1.0, 0.2) << k;
  }
  // The rings' own standard errors widen the error bars, by no more than their relative size.
  RingProfile noisy = rings;
  for (std::size_t i = 0; i < noisy.mean.size(); ++i)
    noisy.stderr_of_mean[i] = 0.05 * noisy.mean[i];
  const LitSphereExitance c =
      lit_sphere_exitance(DiffusionProfile(noisy, m), radius, edges, 20'000, 9);
  for (std::size_t k = 0; k < c.mean.size(); ++k) {
    EXPECT_EQ(c.mean[k], b.mean[k]);
    EXPECT_GT(c.stderr_of_mean[k], b.stderr_of_mean[k]);
    EXPECT_LT(c.stderr_of_mean[k], std::hypot(b.stderr_of_mean[k], 0.05 * b.mean[k]));
  }
  RingProfile bad = rings;
  bad.r_edges[0] = 0.1;
  EXPECT_EQ(field_of([&] { DiffusionProfile(bad, m); }), "rings");
  bad = rings;
  bad.stderr_of_mean.pop_back();
  EXPECT_EQ(field_of([&] { DiffusionProfile(bad, m); }), "rings");
}

TEST(LitSphereExitance, RefusesBadInputNamingTheField) {
  const DiffusionProfile profile(ProfileModel::dipole, medium(0.9, 1.3));
  const std::vector<double> good{0.0, pi};
  EXPECT_EQ(field_of([&] { lit_sphere_exitance(profile, 0.0, good, 10, 1); }), "radius");
  EXPECT_EQ(field_of([&] { lit_sphere_exitance(profile, 1.0, good, 1, 1); }), "samples");
  const std::vector<double> beyond{0.0, 4.0};
  EXPECT_EQ(field_of([&] { lit_sphere_exitance(profile, 1.0, beyond, 10, 1); }), "psi");
  const std::vector<double> backwards{1.0, 0.5};
  EXPECT_EQ(field_of([&] { lit_sphere_exitance(profile, 1.0, backwards, 10, 1); }), "psi");
  EXPECT_EQ(field_of([] { parse_profile_model("jensen", "--model"); }), "--model");
  EXPECT_EQ(field_of([] { DiffusionProfile(ProfileModel::dipole, medium(0.9, 3.0)); }), "eta");
}

}  // namespace
}  // namespace scatterlab
