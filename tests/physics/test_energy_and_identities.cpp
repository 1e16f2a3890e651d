// Energy balance, the angular integral of radiance, agreement of the two estimators, the first
// moment of absorption depth and thread-count independence (fixed seeds; k sigma tolerances).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "simulation_fixtures.hpp"

namespace scatterlab {
namespace {

using testing::expect_all_finite;
using testing::find_tally;
using testing::scalar;
using testing::scalar_error;
using testing::small_beam;

// Volume of the annular cell (ir, .) of the grid, in mfp^3.
double cell_volume(const Grid& grid, std::size_t ir) {
  const double r0 = grid.r.edge(static_cast<int>(ir)), r1 = grid.r.edge(static_cast<int>(ir) + 1);
  return std::numbers::pi * (r1 * r1 - r0 * r0) * grid.z.width();
}

class EstimatorTest : public ::testing::TestWithParam<Estimator> {};

TEST_P(EstimatorTest, AbsorbedPowerFromFluenceIsOne) {
  // integral of sigma_a phi dV over the grid, plus what is absorbed outside it, is the incident
  // power: 1 within 4 sigma (sigma from the batch spread of both terms).
  InfiniteMediumSpec spec = small_beam(0.5, 0.9, 2000000);
  spec.tallies.estimator = GetParam();
  spec.tallies.radiance = false;
  const TransportOutput out = run_infinite_medium(spec);
  const TallyResult& fluence = find_tally(out, "fluence");
  double absorbed = 0.0, variance = 0.0;
  const double sigma_a = spec.medium.sigma_a();
  for (std::size_t i = 0; i < fluence.size(); ++i) {
    const double v = cell_volume(spec.grid, i / fluence.shape[1]);
    absorbed += sigma_a * fluence.mean[i] * v;
    // Cells are positively correlated through shared photons: add errors linearly (an upper
    // bound) rather than in quadrature.
    variance += sigma_a * fluence.stderr_of_mean[i] * v;
  }
  const double outside = scalar(out, "absorbed_outside_grid");
  const double tolerance = 4.0 * (variance + scalar_error(out, "absorbed_outside_grid"));
  EXPECT_NEAR(absorbed + outside, 1.0, tolerance);
  EXPECT_LT(tolerance, 0.03);  // the check has teeth
  // Analog absorption: every photon ends absorbed somewhere, exactly.
  EXPECT_DOUBLE_EQ(scalar(out, "absorbed") + outside, 1.0);
}

TEST_P(EstimatorTest, RadianceIntegratedOverAnglesIsTheFluence) {
  InfiniteMediumSpec spec = small_beam(0.7, 0.5, 50000);
  spec.tallies.estimator = GetParam();
  const TransportOutput out = run_infinite_medium(spec);
  const TallyResult& radiance = find_tally(out, "radiance");
  const TallyResult& fluence = find_tally(out, "fluence");
  const Grid& grid = spec.grid;
  const std::size_t angles = radiance.shape[2] * radiance.shape[3];
  for (std::size_t cell = 0; cell < fluence.size(); ++cell) {
    double integral = 0.0;
    for (std::size_t a = 0; a < angles; ++a) {
      const int itheta = static_cast<int>(a / radiance.shape[3]);
      const double solid_angle = (std::cos(grid.theta.edge(itheta)) - std::cos(grid.theta.edge(itheta + 1))) *
                                 grid.phi.width();
      integral += radiance.mean[cell * angles + a] * solid_angle;
    }
    ASSERT_NEAR(integral, fluence.mean[cell], 1e-12 * (1.0 + fluence.mean[cell])) << cell;
  }
}

TEST_P(EstimatorTest, AbsorptionDepthMatchesTheFirstMoment) {
  // Mean absorption depth of a beam: flight n has mean length 1 and mean direction cosine g^n,
  // and is flown with probability albedo^n, so <z_abs> = sum_n (albedo g)^n = 1 / (1 - albedo g).
  for (double g : {-0.999, -1e-9, 0.0, 0.3, 0.9, 0.999}) {
    for (double albedo : {0.0, 1e-6, 0.5, 0.95}) {
      InfiniteMediumSpec spec = small_beam(albedo, g, 100000);
      spec.tallies.estimator = GetParam();
      spec.tallies.radiance = false;
      const TransportOutput out = run_infinite_medium(spec);
      expect_all_finite(out);
      const double expected = 1.0 / (1.0 - albedo * g);
      EXPECT_NEAR(scalar(out, "absorbed_mean_depth"), expected,
                  4.5 * scalar_error(out, "absorbed_mean_depth"))
          << "g = " << g << ", albedo = " << albedo;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(BothEstimators, EstimatorTest,
                         ::testing::Values(Estimator::collision, Estimator::track_length),
                         [](const auto& param_info) { return to_string(param_info.param); });

TEST(Estimators, CollisionAndTrackLengthAgree) {
  // Independent runs (different seeds) of the two estimators: every fluence, flux and radiance
  // bin agrees within 5 combined sigma, and the mean squared z-score is near 1.
  InfiniteMediumSpec spec = small_beam(0.5, 0.9, 300000);
  spec.grid.r.bins = 6;
  spec.grid.z.bins = 8;
  InfiniteMediumSpec track = spec;
  track.tallies.estimator = Estimator::track_length;
  track.run.seed = 2;
  const TransportOutput a = run_infinite_medium(spec), b = run_infinite_medium(track);
  for (const char* name : {"fluence", "flux", "radiance"}) {
    const TallyResult& x = find_tally(a, name);
    const TallyResult& y = find_tally(b, name);
    double sum_z2 = 0.0;
    std::size_t used = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double sigma = std::hypot(x.stderr_of_mean[i], y.stderr_of_mean[i]);
      if (sigma == 0.0 || x.stderr_of_mean[i] == 0.0) continue;  // bins no collision reached
      const double z = (x.mean[i] - y.mean[i]) / sigma;
      EXPECT_LT(std::abs(z), 5.0) << name << "[" << i << "]";
      sum_z2 += z * z;
      ++used;
    }
    ASSERT_GT(used, x.size() / 2) << name;
    EXPECT_NEAR(sum_z2 / static_cast<double>(used), 1.0, 0.35) << name;
  }
}

TEST(Determinism, SameSeedIsBitwiseIdenticalOnOneAndTwoThreads) {
  for (Estimator estimator : {Estimator::collision, Estimator::track_length}) {
    InfiniteMediumSpec spec = small_beam(0.8, 0.9, 20000);
    spec.tallies.estimator = estimator;
    spec.tallies.split_by_order = true;
    spec.run.batches = 7;  // not a multiple of the thread count
    InfiniteMediumSpec one = spec, two = spec;
    one.run.threads = 1;
    two.run.threads = 2;
    const TransportOutput a = run_infinite_medium(one), b = run_infinite_medium(two);
    ASSERT_EQ(a.tallies.size(), b.tallies.size());
    for (std::size_t k = 0; k < a.tallies.size(); ++k) {
      EXPECT_EQ(a.tallies[k].mean, b.tallies[k].mean) << a.tallies[k].name;
      EXPECT_EQ(a.tallies[k].stderr_of_mean, b.tallies[k].stderr_of_mean) << a.tallies[k].name;
    }
    EXPECT_EQ(a.scattering_events, b.scattering_events);
  }
}

TEST(ScatteringOrders, PartsAddUpToTheTotal) {
  InfiniteMediumSpec spec = small_beam(0.6, 0.9, 50000);
  spec.tallies.split_by_order = true;
  const TransportOutput out = run_infinite_medium(spec);
  for (const char* name : {"radiance", "fluence", "flux"}) {
    const std::string base = name;
    const TallyResult& total = find_tally(out, base);
    const TallyResult& u = find_tally(out, base + "_unscattered");
    const TallyResult& s = find_tally(out, base + "_single");
    const TallyResult& m = find_tally(out, base + "_multiple");
    for (std::size_t i = 0; i < total.size(); ++i) {
      ASSERT_NEAR(u.mean[i] + s.mean[i] + m.mean[i], total.mean[i], 1e-12 * (1 + std::abs(total.mean[i])));
    }
  }
  // Unscattered light of a beam travels along the axis only: nothing off the axis bin.
  const TallyResult& u = find_tally(out, "fluence_unscattered");
  for (std::size_t i = u.shape[1]; i < u.size(); ++i) EXPECT_EQ(u.mean[i], 0.0);
}

TEST(EscapeRadius, AlbedoOneEndsOnlyByEscaping) {
  InfiniteMediumSpec spec = small_beam(1.0, 0.9, 2000);
  spec.run.escape_radius = 5.0;
  spec.tallies.radiance = false;
  const TransportOutput out = run_infinite_medium(spec);
  expect_all_finite(out);
  EXPECT_EQ(scalar(out, "escaped"), 1.0);
  EXPECT_EQ(scalar(out, "absorbed"), 0.0);
  EXPECT_EQ(scalar(out, "absorbed_outside_grid"), 0.0);
}

TEST(ExtremeCases, RunWithoutNanAndConserveEnergy) {
  for (double albedo : {0.0, 1e-6, 0.9999}) {
    for (double g : {-0.999, -1e-9, 0.0, 1e-9, 0.999}) {
      InfiniteMediumSpec spec = small_beam(albedo, g, albedo > 0.99 ? 400 : 4000);
      for (Estimator estimator : {Estimator::collision, Estimator::track_length}) {
        spec.tallies.estimator = estimator;
        const TransportOutput out = run_infinite_medium(spec);
        expect_all_finite(out);
        EXPECT_DOUBLE_EQ(scalar(out, "absorbed") + scalar(out, "absorbed_outside_grid"), 1.0);
        const double expected = 1.0 / (1.0 - albedo * g);
        EXPECT_NEAR(scalar(out, "absorbed_mean_depth"), expected,
                    5.0 * scalar_error(out, "absorbed_mean_depth") + 1e-12)
            << "albedo " << albedo << " g " << g;
      }
    }
  }
}

}  // namespace
}  // namespace scatterlab
