// Vavassori §4.2's findings, on a simulated beam (g = 0.9, albedo 0.5, fixed seed): the double
// exponential fits the lobes better than the spherical Gaussian (it captures the "diffuse"
// part, Figs. 4.7 and 4.10), and the anisotropic double exponential better than both near the
// source, where the lobes are flattened across the phi = 0 plane (Fig. 4.6).
#include <gtest/gtest.h>

#include "scatterlab/fit/lobe_fits_file.hpp"
#include "simulation_fixtures.hpp"

namespace scatterlab {
namespace {

using fit::LobeModel;

const fit::ModelFits& model_fits(const fit::LobeFitRun& run, LobeModel model) {
  for (const fit::ModelFits& fits : run.models) {
    if (fits.model == model) return fits;
  }
  throw std::logic_error("model not run");
}

// The radiance and flux of a simulated beam, as scatterlab fit reads them from its file.
fit::RadianceLobes simulated_lobes(const InfiniteMediumSpec& spec) {
  const TransportOutput output = run_infinite_medium(spec);
  const TallyResult& radiance = testing::find_tally(output, "radiance");
  const TallyResult& flux = testing::find_tally(output, "flux");
  fit::RadianceLobes lobes;
  lobes.r_edges = spec.grid.r.edges();
  lobes.z_edges = spec.grid.z.edges();
  lobes.theta_edges = spec.grid.theta.edges();
  lobes.phi_edges = spec.grid.phi.edges();
  lobes.mean = radiance.mean;
  lobes.stderr_of_mean = radiance.stderr_of_mean;
  for (std::size_t i = 0; i < flux.mean.size(); i += 2) {
    lobes.flux.insert(lobes.flux.end(), {flux.mean[i], 0.0, flux.mean[i + 1]});
  }
  return lobes;
}

TEST(LobeFitsOnSimulation, DoubleExponentialBeatsSgAndAnisotropyBeatsBoth) {
  InfiniteMediumSpec spec = testing::small_beam(0.5, 0.9, 1'000'000);
  spec.grid.r = {0.0, 1.5, 5};
  spec.grid.z = {-1.0, 3.0, 8};
  spec.grid.theta.bins = 18;
  spec.grid.phi.bins = 36;
  const fit::RadianceLobes lobes = simulated_lobes(spec);
  const fit::LobeGrid grid(lobes.theta_edges, lobes.phi_edges, false);
  const fit::LobeFitRun run =
      fit::fit_lobes(lobes, grid, {LobeModel::sg, LobeModel::dexp, LobeModel::adexp}, {}, 2);
  const fit::LobeFitSummary summary = fit::summarize(run);
  ASSERT_EQ(summary.models.size(), 3u);
  for (const fit::ModelFitSummary& s : summary.models) {
    EXPECT_GE(s.fitted, 35u) << fit::to_string(s.model);  // of 40 bins
    EXPECT_EQ(s.failed, 0u) << fit::to_string(s.model);
  }
  const double sg = summary.models[0].median_error, dexp = summary.models[1].median_error,
               adexp = summary.models[2].median_error;
  EXPECT_LT(dexp, sg);
  EXPECT_LT(adexp, 0.7 * dexp);
  EXPECT_GT(summary.dexp_beats_sg, 0.6);
  EXPECT_GT(summary.adexp_beats_sg_and_dexp, 0.6);

  // Near the source (r < 0.6 mfp, 0 < z < 1.5 mfp) the lobes are flattened: eta < 0.
  const fit::ModelFits& anisotropic = model_fits(run, LobeModel::adexp);
  for (std::size_t r = 0; r < 2; ++r) {
    for (std::size_t z = 2; z < 5; ++z) {
      const fit::LobeFit& f = anisotropic.fits[r * 8 + z];
      ASSERT_TRUE(fit::usable(f.status)) << r << " " << z;
      EXPECT_LT(f.parameters.shape[3], -0.5) << r << " " << z;
    }
  }
}

// Near the beam beyond a mean free path (r < 0.4, z = 1-2.2 mfp) the multiply scattered light
// is two lobes, a forward cone about the beam beside the light spreading from the ridge:
// adexp_ridge is off by up to several times the noise there, while adexp2_ridge, its superset
// with a second lobe, comes within 2x of it (as on the README's 1e8-photon beam, whose grid
// this one shares in r and z).
TEST(LobeFitsOnSimulation, SecondLobeReachesTheNoiseNearTheBeam) {
  InfiniteMediumSpec spec = testing::small_beam(0.5, 0.9, 100'000'000);
  spec.grid.r = {0.0, 0.4, 4};
  spec.grid.z = {1.0, 2.2, 12};
  spec.grid.theta.bins = 18;
  spec.grid.phi.bins = 36;
  const fit::RadianceLobes lobes = simulated_lobes(spec);
  const fit::LobeGrid grid(lobes.theta_edges, lobes.phi_edges, false);
  const fit::LobeFitRun run =
      fit::fit_lobes(lobes, grid, {LobeModel::adexp_ridge, LobeModel::adexp2_ridge}, {}, 2);
  const fit::ModelFits& one = model_fits(run, LobeModel::adexp_ridge);
  const fit::ModelFits& two = model_fits(run, LobeModel::adexp2_ridge);
  std::size_t one_within = 0, two_within = 0;
  for (std::size_t bin = 0; bin < 48; ++bin) {
    ASSERT_TRUE(fit::usable(two.fits[bin].status)) << two.fits[bin].message;
    EXPECT_LE(two.fits[bin].cost, one.fits[bin].cost * (1.0 + 1e-9)) << bin;  // a superset
    one_within += one.fits[bin].error_sphere <= 2.0 * one.fits[bin].noise;
    two_within += two.fits[bin].error_sphere <= 2.0 * two.fits[bin].noise;
  }
  // Measured: 42 of the 48 bins for adexp2_ridge (the misses are bins at the grid's first z,
  // which start without a neighbour's solution, and three at r = 0.3-0.4, z = 1.0-1.3), 3 for
  // adexp_ridge. The count moves by a few bins with round-off: e^x - 1 computed as exp(x) - 1
  // instead of expm1(x) in the node loop (a change of 2e-13 of it) gave 38, as Levenberg-Marquardt
  // ends in another of near-equal minima; hence the margin.
  EXPECT_GE(two_within, 34u);
  EXPECT_LE(one_within, 12u);
}

}  // namespace
}  // namespace scatterlab
