// Light against time: declared tallies with a time-of-flight filter (transport/declared_tally.hpp)
// held against exact results. Fixed seeds; tolerances k sigma.

#include <gtest/gtest.h>

#include <cmath>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/transport/layered_slab.hpp"
#include "scatterlab/transport/searchlight.hpp"
#include "simulation_fixtures.hpp"

namespace scatterlab {
namespace {

using testing::find_tally;
using testing::scalar;

DeclaredFilter filter(Coordinate coordinate, const UniformAxis& axis) {
  return {coordinate, axis.min, axis.max, axis.bins};
}

// In an infinite medium every photon is absorbed, and its path length is a sum of a geometric
// number (mean 1 / (1 - albedo)) of exponential flights of mean 1 / sigma_t: exponential itself,
// of rate (1 - albedo) sigma_t = mu_a, whatever the phase function. So the power absorbed against
// time after a unit impulse is exactly mu_a v exp(-mu_a v t), v = c / n, and a bin [t0, t1)
// holds exp(-mu_a v t0) - exp(-mu_a v t1) of it.
TEST(TimeOfFlight, InfiniteMediumAbsorbsExponentiallyInTime) {
  InfiniteMediumSpec spec;
  spec.medium = Medium::from_albedo(0.9, 10.0, 0.8, "mm");  // mu_a = 1 / mm
  spec.tallies.radiance = spec.tallies.fluence = spec.tallies.flux = false;
  spec.run.photons = 200'000;
  spec.run.batches = 20;
  spec.run.seed = 11;
  const double n = 1.4;
  const double rate = 1.0 * speed_of_light * 1e3 / n;  // mu_a v, 1 / s (c in mm / s)
  const UniformAxis time{0.0, 6.0 / rate, 30};
  spec.declared_tallies = {{"absorbed_t", Score::absorbed, {filter(Coordinate::t, time)}, n}};
  const TransportOutput out = run_infinite_medium(spec);
  const TallyResult& a = find_tally(out, "absorbed_t");
  ASSERT_EQ(a.dims, std::vector<std::string>{"t"});
  EXPECT_EQ(a.units, "W per J incident");
  const double width = time.width();
  double mean_time = 0.0, exact_mean_time = 0.0, mean_time_variance = 0.0;
  for (int i = 0; i < time.bins; ++i) {
    const double t0 = time.edge(i), t1 = time.edge(i + 1);
    const double exact = (std::exp(-rate * t0) - std::exp(-rate * t1)) / width;  // W / J
    const auto k = static_cast<std::size_t>(i);
    EXPECT_NEAR(a.mean[k], exact, 4.0 * a.stderr_of_mean[k] + 1e-12 * exact) << "bin " << i;
    // The mean time of the binned curve: bin centres weighted by each bin's share.
    const double centre = time.center(i);
    mean_time += centre * a.mean[k] * width;
    exact_mean_time += centre * exact * width;
    mean_time_variance += std::pow(centre * a.stderr_of_mean[k] * width, 2);
  }
  EXPECT_NEAR(mean_time, exact_mean_time, 4.0 * std::sqrt(mean_time_variance));
  // The binned mean is 1 / (mu_a v) within the bins' width and the 6 / (mu_a v) cut-off.
  EXPECT_NEAR(exact_mean_time, 1.0 / rate, 0.03 / rate);
}

// Summing R(r, t) over its time bins gives R(r) of the same run: the same exits, added in the
// same order, so to round-off. Both equal the geometry's own R(r) ("reflectance") on that grid.
TEST(TimeOfFlight, TimeBinsSumToTheSteadyExitance) {
  HalfSpaceSpec spec;
  spec.medium = Medium::from_albedo(0.5, 2.0, 0.7, "mm");
  spec.eta = 1.4;
  spec.grid.r = UniformAxis{0.0, 2.0, 20};
  spec.run.photons = 40'000;
  spec.run.batches = 8;
  spec.run.seed = 5;
  const DeclaredFilter rings = filter(Coordinate::r, spec.grid.r);
  const DeclaredTally by_time{"reflectance_rt",
                              Score::exitance,
                              {rings, filter(Coordinate::t, UniformAxis{0.0, 1e-6, 50})},
                              std::nullopt};
  const DeclaredTally steady{"reflectance_r", Score::exitance, {rings}, std::nullopt};
  spec.declared_tallies = {by_time, steady};
  const TransportOutput out = run_half_space(spec);
  const TallyResult& rt = find_tally(out, "reflectance_rt");
  const TallyResult& r = find_tally(out, "reflectance_r");
  const TallyResult& own = find_tally(out, "reflectance");
  ASSERT_EQ(rt.shape, (std::vector<std::size_t>{20, 50}));
  EXPECT_EQ(rt.units, "W mm^-2 per J incident");
  EXPECT_EQ(r.units, own.units);
  double total = 0.0;
  for (std::size_t i = 0; i < 20; ++i) {
    double sum = 0.0;
    for (std::size_t j = 0; j < 50; ++j) sum += rt.mean[i * 50 + j] * 1e-6 / 50;
    EXPECT_NEAR(sum, r.mean[i], 1e-12 * r.mean[i]) << "ring " << i;
    EXPECT_NEAR(r.mean[i], own.mean[i], 1e-12 * own.mean[i]) << "ring " << i;
    total += r.mean[i];
  }
  EXPECT_GT(total, 0.0);
}

// Light that crosses a slab without scattering arrives at exactly (sum of n_i d_i) / c: no
// light comes earlier, and in a narrow bin at that time arrives the unscattered transmittance
// (1 - R_sp) (1 - F_12) exp(-sum mu_t,i d_i), F_12 the Fresnel reflectance between the layers
// at normal incidence (light reflected there crosses the slab three times, later).
TEST(TimeOfFlight, UnscatteredLightCrossesASlabAtItsOpticalThickness) {
  LayeredSlabSpec spec;
  spec.length_unit = "mm";
  SlabLayerSpec top, bottom;
  top.mu_a = 0.5;
  top.mu_s = 3.0;
  top.g = 0.0;
  top.n = 1.4;
  top.thickness = 0.2;
  bottom = top;
  bottom.n = 1.5;
  bottom.mu_s = 1.0;
  bottom.thickness = 0.3;
  spec.layers = {top, bottom};
  spec.n_above = 1.0;
  spec.n_below = 1.5;
  spec.run.photons = 100'000;
  spec.run.batches = 10;
  spec.run.seed = 3;
  const double arrival = (1.4 * 0.2 + 1.5 * 0.3) * 1e-3 / speed_of_light;  // s
  const UniformAxis before{0.0, arrival * (1.0 - 1e-9), 1};
  const UniformAxis at{arrival * (1.0 - 1e-9), arrival * (1.0 + 1e-9), 1};
  const DeclaredTally early{
      "early", Score::transmittance, {filter(Coordinate::t, before)}, std::nullopt};
  // By scattering order too: unscattered, and the rest.
  const DeclaredTally on_time{"on_time",
                              Score::transmittance,
                              {filter(Coordinate::t, at), {Coordinate::order, {}, {}, 2}},
                              std::nullopt};
  // And the absorbed power by layer, which is the slab's own: the same absorptions.
  const DeclaredTally layers{
      "absorbed_layers", Score::absorbed, {{Coordinate::layer, {}, {}, 0}}, std::nullopt};
  spec.declared_tallies = {early, on_time, layers};
  const TransportOutput out = run_layered_slab(spec);
  EXPECT_EQ(find_tally(out, "early").mean.at(0), 0.0);
  const TallyResult& t = find_tally(out, "on_time");
  ASSERT_EQ(t.dims, (std::vector<std::string>{"t", "order"}));
  EXPECT_EQ(t.mean.at(1), 0.0);  // none of it has scattered
  const double width = at.width();
  const double exact = (1.0 - fresnel_dielectric_reflectance(1.0, 1.4)) *
                       (1.0 - fresnel_dielectric_reflectance(1.0, 1.5 / 1.4)) *
                       std::exp(-3.5 * 0.2 - 1.5 * 0.3);
  EXPECT_NEAR(t.mean.at(0) * width, exact, 4.0 * t.stderr_of_mean.at(0) * width);
  // And no more than the unscattered transmittance of the run, which also holds the light
  // reflected between the layers.
  EXPECT_LE(t.mean.at(0) * width, scalar(out, "total_transmittance_unscattered") * (1 + 1e-12));
  const TallyResult& declared = find_tally(out, "absorbed_layers");
  const TallyResult& own = find_tally(out, "absorbed_by_layer");
  ASSERT_EQ(declared.shape, own.shape);
  for (std::size_t i = 0; i < own.size(); ++i) {
    EXPECT_NEAR(declared.mean[i], own.mean[i], 1e-12 * own.mean[i]) << "layer " << i;
  }
}

// Late light in a semi-infinite medium decays as diffusion theory says (Patterson, Chance & Wilson
// 1989, Eq. 7): R(rho, t) = (4 pi D v)^-3/2 z0 t^-5/2 exp(-mu_a v t) exp(-(rho^2 + z0^2) / (4 D v
// t)), D = 1 / (3 (mu_a + mu_s')), z0 = 1 / mu_s'. Its late slope is what time-domain instruments
// read mu_a from. The regime where the theory holds, and the test's: mu_s' / mu_a = 100, an index-
// matched surface (Patterson's boundary), light that has flown 150 to 450 transport mean free
// paths (100 to 300 ps), collected over a disc of 15 of them. There the ratio of the light in two
// late time bins agrees with the theory's to 5 % (the theory's own error, stated here as the
// tolerance), plus 3 sigma.
TEST(TimeOfFlight, LateReflectanceDecaysAsDiffusionTheorySays) {
  HalfSpaceSpec spec;
  const double mu_a = 0.05, mu_s = 5.0;  // 1 / mm, g = 0
  spec.medium = Medium::from_coefficients(mu_a, mu_s, 0.0, "mm");
  spec.eta = 1.0;
  spec.grid.r = UniformAxis{0.0, 3.0, 1};
  spec.grid.theta_o = UniformAxis{0.0, pi / 2, 1};
  spec.tallies.fluence = false;
  spec.run.photons = 4'000'000;
  spec.run.batches = 10;
  spec.run.seed = 2;
  const double t0 = 100e-12, t1 = 150e-12, t2 = 200e-12;
  spec.declared_tallies = {{"late",
                            Score::exitance,
                            {filter(Coordinate::r, UniformAxis{0.0, 3.0, 1}),
                             filter(Coordinate::t, UniformAxis{t0, t2, 2})},
                            std::nullopt}};
  const TransportOutput out = run_half_space(spec);
  const TallyResult& late = find_tally(out, "late");
  const double v = speed_of_light * 1e3;  // mm / s, n = 1
  const double d = 1.0 / (3.0 * (mu_a + mu_s)), z0 = 1.0 / mu_s, ring = 3.0;
  // Over the disc r < 3 mm, the theory's R integrates in closed form in rho:
  // int 2 pi rho exp(-rho^2 / (4 D v t)) = 4 pi D v t (1 - exp(-ring^2 / (4 D v t))).
  const auto disc = [&](double t) {
    const double spread = 4.0 * d * v * t;
    return std::pow(4.0 * pi * d * v, -1.5) * z0 * std::pow(t, -2.5) * std::exp(-mu_a * v * t) *
           std::exp(-z0 * z0 / spread) * pi * spread * (1.0 - std::exp(-ring * ring / spread));
  };
  const auto in_bin = [&](double a, double b) {  // Simpson's rule, 400 intervals
    const int n = 400;
    const double h = (b - a) / n;
    double sum = disc(a) + disc(b);
    for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * disc(a + i * h);
    return sum * h / 3.0;
  };
  const double theory = std::log(in_bin(t1, t2) / in_bin(t0, t1));
  ASSERT_GT(late.mean[0], 0.0);
  ASSERT_GT(late.mean[1], 0.0);
  const double measured = std::log(late.mean[1] / late.mean[0]);
  const double sigma =
      std::hypot(late.stderr_of_mean[0] / late.mean[0], late.stderr_of_mean[1] / late.mean[1]);
  EXPECT_NEAR(measured, theory, 0.05 + 3.0 * sigma) << "sigma " << sigma;
}

}  // namespace
}  // namespace scatterlab
