// The lit sphere (transport/lit_object.hpp, transport/sphere.hpp): an absorbing sphere against
// the closed-form attenuation of its chords, index-matched and behind a Fresnel interface; the
// energy balance photon by photon; and a large sphere under a beam at its pole against the
// half-space's searchlight (fixed seeds; k sigma tolerances).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/quadrature.hpp"
#include "scatterlab/transport/lit_object.hpp"
#include "scatterlab/transport/searchlight.hpp"
#include "simulation_fixtures.hpp"

namespace scatterlab {
namespace {

constexpr double kPi = std::numbers::pi;

using testing::find_tally;
using testing::scalar;
using testing::scalar_error;

LitObjectSpec sphere(double albedo, double g, double eta, double radius, std::uint64_t photons) {
  LitObjectSpec spec;
  spec.medium.albedo = albedo;
  spec.medium.g = g;
  spec.eta = eta;
  spec.radius = radius;
  spec.run.photons = photons;
  spec.run.batches = 32;
  spec.run.threads = 2;
  return spec;
}

// Light that meets the sphere at cos theta_i = mu (the shadow disk is uniform in b^2 = R^2 (1 -
// mu^2): density 2 mu d mu) is reflected with F, else enters along cos theta_t and crosses a
// chord of 2 R cos theta_t; every later hit is at the same angle, where it leaves with 1 - F
// (F is the same from either side) or is reflected into an equal chord. Without scattering:
//   reflected at entry  int_0^1 F 2 mu d mu,
//   exited              int_0^1 (1 - F)^2 e^{-L} / (1 - F e^{-L}) 2 mu d mu,  L = 2 R cos theta_t.
struct ChordTotals {
  double reflected, exited;
};
ChordTotals absorbing_sphere(double radius, double eta) {
  const auto reflected = [eta](double mu) {
    return 2.0 * mu * fresnel_dielectric_reflectance(mu, eta);
  };
  const auto exited = [eta, radius](double mu) {
    const FresnelDielectric entry = fresnel_dielectric_terms(mu, eta);
    if (entry.total_internal_reflection) return 0.0;
    const double f = entry.reflectance(),
                 attenuation = std::exp(-2.0 * radius * entry.cos_transmitted);
    return 2.0 * mu * (1.0 - f) * (1.0 - f) * attenuation / (1.0 - f * attenuation);
  };
  // Below eta < 1, light beyond the critical angle cannot enter: a kink at its cosine.
  const double critical = eta < 1.0 ? std::sqrt(1.0 - eta * eta) : 0.5;
  const double breaks[] = {0.0, critical, 1.0};
  return {integrate_adaptive(reflected, breaks).value, integrate_adaptive(exited, breaks).value};
}

TEST(LitSphere, IndexMatchedAbsorbingSphereTransmitsItsChords) {
  // eta = 1, albedo 0: light at impact parameter b crosses the chord 2 R mu, mu = sqrt(1 -
  // b^2/R^2), and leaves at the far point with cos psi = -mu. The power leaving the zone
  // mu in [m0, m1] is int 2 mu e^{-2 R mu} d mu = [-(1 + c mu) e^{-c mu} 2 / c^2], c = 2 R.
  const double radius = 0.7;
  LitObjectSpec spec = sphere(0.0, 0.0, 1.0, radius, 400'000);
  spec.psi.bins = 12;
  const TransportOutput out = run_lit_sphere(spec);
  const double c = 2.0 * radius;
  const auto primitive = [c](double mu) {
    return -2.0 / (c * c) * (1.0 + c * mu) * std::exp(-c * mu);
  };
  EXPECT_NEAR(scalar(out, "exited"), primitive(1.0) - primitive(0.0),
              4.0 * scalar_error(out, "exited"));
  EXPECT_LT(scalar_error(out, "exited"), 1e-3);
  EXPECT_NEAR(scalar(out, "absorbed"), 1.0 - scalar(out, "exited"), 1e-12);
  EXPECT_EQ(scalar(out, "reflected_at_entry"), 0.0);
  EXPECT_EQ(scalar(out, "exited_single"), 0.0);
  EXPECT_EQ(scalar(out, "absorbed_unscattered"), scalar(out, "absorbed"));  // nothing scatters

  const TallyResult& exitance = find_tally(out, "exitance");
  for (int k = 0; k < spec.psi.bins; ++k) {
    const double psi0 = spec.psi.edge(k), psi1 = spec.psi.edge(k + 1);
    const double area = 2.0 * kPi * radius * radius * (std::cos(psi0) - std::cos(psi1));
    // mu = -cos psi, from the far hemisphere only.
    const double m0 = std::max(0.0, -std::cos(psi0)), m1 = std::max(0.0, -std::cos(psi1));
    const double power = primitive(m1) - primitive(m0);
    const auto i = static_cast<std::size_t>(k);
    EXPECT_NEAR(exitance.mean[i] * area, power, 4.0 * exitance.stderr_of_mean[i] * area + 1e-15)
        << "zone " << k;
  }
}

TEST(LitSphere, AbsorbingSphereBehindFresnelMatchesTheFresnelWeightedChords) {
  for (const double eta : {1.5, 0.8}) {
    const double radius = 0.5;
    const TransportOutput out = run_lit_sphere(sphere(0.0, 0.0, eta, radius, 400'000));
    const ChordTotals exact = absorbing_sphere(radius, eta);
    EXPECT_NEAR(scalar(out, "reflected_at_entry"), exact.reflected,
                4.0 * scalar_error(out, "reflected_at_entry"))
        << "eta " << eta;
    EXPECT_NEAR(scalar(out, "exited"), exact.exited, 4.0 * scalar_error(out, "exited"))
        << "eta " << eta;
    EXPECT_LT(scalar_error(out, "exited"), 1e-3);
  }
}

TEST(LitSphere, AbsorbingSphereBehindFresnelPutsItsChordsWhereSnellSays) {
  // Zone by zone, the light of one impact parameter enters at psi = i (cos i = mu), crosses
  // chords of central angle pi - 2t, and after k internal reflections leaves at
  // psi = i + (k + 1)(pi - 2t), folded into [0, pi] (past the far pole it is on the other side),
  // with power (1 - F)^2 F^k e^{-(k + 1) L}. The exit points crowd on a caustic ring where
  // d psi / d i = 0 (156.4 degrees for k = 0 at eta 1.3; 138.6 at eta 1.5). The power per zone
  // is integrated over the shadow disk (uniform in b^2 / R^2 = 1 - mu^2) by the midpoint rule
  // on 2e5 points: an independent evaluation of where Snell's law puts the light.
  const double radius = 0.5, eta = 1.5;
  LitObjectSpec spec = sphere(0.0, 0.0, eta, radius, 400'000);
  spec.psi.bins = 36;
  const TransportOutput out = run_lit_sphere(spec);
  std::vector<double> power(static_cast<std::size_t>(spec.psi.bins), 0.0);
  const int points = 200'000;
  for (int n = 0; n < points; ++n) {
    const double u = (n + 0.5) / points;  // b^2 / R^2
    const double mu = std::sqrt(1.0 - u);
    const FresnelDielectric entry = fresnel_dielectric_terms(mu, eta);
    const double f = entry.reflectance(), t = std::acos(entry.cos_transmitted);
    const double attenuation = std::exp(-2.0 * radius * entry.cos_transmitted);
    double weight = (1.0 - f) * (1.0 - f) * attenuation / points;
    double angle = std::acos(mu);
    for (int k = 0; weight > 1e-18 * (1.0 / points); ++k) {
      angle += kPi - 2.0 * t;
      double folded = std::fmod(angle, 2.0 * kPi);
      if (folded > kPi) folded = 2.0 * kPi - folded;
      power[static_cast<std::size_t>(spec.psi.index(folded))] += weight;
      weight *= f * attenuation;
    }
  }
  const TallyResult& exitance = find_tally(out, "exitance");
  for (int k = 0; k < spec.psi.bins; ++k) {
    const double area =
        2.0 * kPi * radius * radius * (std::cos(spec.psi.edge(k)) - std::cos(spec.psi.edge(k + 1)));
    const auto i = static_cast<std::size_t>(k);
    // A zone holds a photon with probability power[i]: binomial errors, which hold for zones
    // too faint to have caught a photon (no tally stderr) as well.
    const double sigma = std::sqrt(power[i] * (1.0 - power[i]) / 400'000.0);
    EXPECT_NEAR(exitance.mean[i] * area, power[i], 4.0 * sigma + 1e-6 * power[i]) << "zone " << k;
  }
}

TEST(LitSphere, EnergyBalancesPhotonByPhotonAndOrdersSum) {
  for (const ObjectLight light : {ObjectLight::directional, ObjectLight::pole_beam}) {
    for (const double eta : {1.0, 1.4, 0.7, 3.0}) {  // 3: most of the sphere totally reflects
      LitObjectSpec spec = sphere(0.9, 0.7, eta, 2.0, 50'000);
      spec.light = light;
      const TransportOutput out = run_lit_sphere(spec);
      const std::string label = to_string(light) + " eta " + std::to_string(eta);
      testing::expect_lit_object_balance(out, label);
      // The exitance over the whole surface is the light that exited.
      const TallyResult& exitance = find_tally(out, "exitance");
      double total = 0.0;
      for (int k = 0; k < spec.psi.bins; ++k) {
        total += exitance.mean[static_cast<std::size_t>(k)] * 2.0 * kPi * spec.radius *
                 spec.radius * (std::cos(spec.psi.edge(k)) - std::cos(spec.psi.edge(k + 1)));
      }
      EXPECT_NEAR(total, scalar(out, "exited"), 1e-12) << label;
    }
  }
}

TEST(LitSphere, LargeSphereUnderAPoleBeamIsTheHalfSpace) {
  // A convex surface lets more light out than its tangent plane, by a fraction of order (the
  // distance light travels inside) / R: measured here (albedo 0.9, 2e6 photons) as +0.060,
  // +0.0056 and +0.0011 of the diffuse reflectance 0.285 at R = 10, 100 and 1000 mfp. At R = 1e4
  // mfp that is ~5e-5, below the runs' errors: the zones psi R within 3 mfp of the pole must hold
  // the half-space's R_d(r) rings, and the totals must agree, within the combined errors. (The
  // sphere's zones and the plane's rings differ in area by (sin x / x) factors of (r/R)^2.)
  const double radius = 1e4;
  LitObjectSpec spec = sphere(0.9, 0.0, 1.3, radius, 300'000);
  spec.light = ObjectLight::pole_beam;
  spec.psi.bins = 100'000;
  const double width = kPi * radius / spec.psi.bins;
  const TransportOutput curved = run_lit_sphere(spec);

  HalfSpaceSpec flat;
  flat.medium = spec.medium;
  flat.eta = 1.3;
  flat.run = spec.run;
  flat.run.seed = 7;
  flat.grid.r = {0.0, 10.0 * width, 10};
  flat.tallies.fluence = false;
  const TransportOutput plane = run_half_space(flat);

  EXPECT_DOUBLE_EQ(scalar(curved, "reflected_at_entry"), scalar(plane, "specular_reflectance"));
  const TallyResult& exitance = find_tally(curved, "exitance");
  const TallyResult& reflectance = find_tally(plane, "reflectance");
  for (std::size_t k = 0; k < 10; ++k) {
    const double combined = std::hypot(exitance.stderr_of_mean[k], reflectance.stderr_of_mean[k]);
    EXPECT_NEAR(exitance.mean[k], reflectance.mean[k], 4.0 * combined) << "ring " << k;
  }
  const double combined =
      std::hypot(scalar_error(curved, "exited"), scalar_error(plane, "diffuse_reflectance"));
  EXPECT_NEAR(scalar(curved, "exited"), scalar(plane, "diffuse_reflectance"), 4.0 * combined);
  EXPECT_LT(combined, 2e-3);
}

TEST(LitSphere, ABeamFromOutsideIsRefractedWhereItMeetsTheSphere) {
  // Aimed at the lit pole along the normal it is the pole beam, bit for bit.
  LitObjectSpec pole = sphere(0.9, 0.5, 1.3, 1.5, 20'000);
  pole.light = ObjectLight::pole_beam;
  LitObjectSpec aimed = pole;
  aimed.light = ObjectLight::beam;
  aimed.beam_origin = {0.0, 0.0, -4.0};
  aimed.beam_direction = {0.0, 0.0, 2.0};
  const TransportOutput a = run_lit_sphere(pole), b = run_lit_sphere(aimed);
  ASSERT_EQ(a.tallies.size(), b.tallies.size());
  for (std::size_t t = 0; t < a.tallies.size(); ++t) {
    EXPECT_EQ(a.tallies[t].mean, b.tallies[t].mean) << a.tallies[t].name;
    EXPECT_EQ(a.tallies[t].stderr_of_mean, b.tallies[t].stderr_of_mean) << a.tallies[t].name;
  }
  // Off the axis it meets the surface at cos theta_i = sqrt(1 - (x / R)^2): F of that angle is
  // reflected, exactly, and every photon that entered ends exited or absorbed.
  LitObjectSpec oblique = aimed;
  oblique.beam_origin = {0.9, 0.0, -4.0};
  oblique.beam_direction = {0.0, 0.0, 1.0};
  const TransportOutput out = run_lit_sphere(oblique);
  const double cos_incidence = std::sqrt(1.0 - 0.9 * 0.9 / (1.5 * 1.5));
  EXPECT_NEAR(scalar(out, "reflected_at_entry"), fresnel_dielectric_reflectance(cos_incidence, 1.3),
              1e-12);
  EXPECT_NEAR(scalar(out, "reflected_at_entry") + scalar(out, "exited") + scalar(out, "absorbed"),
              1.0, 1e-12);
}

TEST(LitSphere, ExitanceByAzimuthSumsToTheZonesAndMirrorsAnOffAxisBeam) {
  // Binning draws no random number: the same photons with 8 azimuth bins sum, patch by patch
  // times area, to the zones of one bin.
  LitObjectSpec spec = sphere(0.9, 0.5, 1.3, 1.0, 100'000);
  spec.light = ObjectLight::beam;
  spec.beam_origin = {0.6, 0.0, -3.0};
  spec.beam_direction = {0.0, 0.0, 1.0};
  spec.psi.bins = 12;
  const TransportOutput zones = run_lit_sphere(spec);
  spec.azimuth.bins = 8;
  const TransportOutput patches = run_lit_sphere(spec);
  const TallyResult& zone = find_tally(zones, "exitance");
  const TallyResult& patch = find_tally(patches, "exitance");
  ASSERT_EQ(patch.shape, (std::vector<std::size_t>{12, 8}));
  for (std::size_t k = 0; k < 12; ++k) {
    double sum = 0.0;
    for (std::size_t a = 0; a < 8; ++a) sum += patch.mean[k * 8 + a] / 8.0;  // equal areas
    EXPECT_NEAR(sum, zone.mean[k], 1e-12 * (1.0 + zone.mean[k])) << "zone " << k;
    // The beam lies in the x-z plane: azimuth a and 2 pi - a are mirror images.
    for (std::size_t a = 0; a < 4; ++a) {
      const std::size_t i = k * 8 + a, j = k * 8 + (7 - a);
      EXPECT_NEAR(patch.mean[i], patch.mean[j],
                  4.0 * std::hypot(patch.stderr_of_mean[i], patch.stderr_of_mean[j]) + 1e-15)
          << "zone " << k << ", azimuth bin " << a;
    }
  }
}

TEST(LitSphere, BadSpecsNameTheField) {
  LitObjectSpec spec;
  spec.radius = -1.0;
  EXPECT_THROW(spec.validate(), InputError);
  spec = LitObjectSpec{};
  spec.eta = 0.0;
  EXPECT_THROW(spec.validate(), InputError);
  spec = LitObjectSpec{};
  spec.psi.max = 1.0;
  EXPECT_THROW(spec.validate(), InputError);
  spec = LitObjectSpec{};
  spec.light = ObjectLight::beam;
  spec.beam_direction = {1.0, 0.0, 0.0};  // from (0, 0, -2): passes the sphere by
  EXPECT_THROW(spec.validate(), InputError);
  spec.beam_direction = {0.0, 0.0, 1.0};
  spec.beam_origin = {0.0, 0.0, -0.5};  // inside
  EXPECT_THROW(spec.validate(), InputError);
  spec.beam_origin = {0.0, 0.0, -2.0};
  EXPECT_NO_THROW(spec.validate());
}

}  // namespace
}  // namespace scatterlab
