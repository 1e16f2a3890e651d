// Isotropic point source, isotropic scattering, infinite medium: the Monte Carlo fluence on
// spherical shells against the exact transport solution (models/point_source_exact.hpp), shell
// by shell over rho in [0.05, 10] mfp, for albedos from 0.01 to 0.99 and both estimators.
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "scatterlab/models/point_source_exact.hpp"
#include "simulation_fixtures.hpp"

namespace scatterlab {
namespace {

class PointSourceTest : public ::testing::TestWithParam<std::tuple<double, Estimator>> {};

TEST_P(PointSourceTest, ShellFluenceMatchesTheExactSolution) {
  const auto [albedo, estimator] = GetParam();
  InfiniteMediumSpec spec;
  spec.source = SourceKind::point;
  spec.medium.albedo = albedo;
  spec.medium.g = 0.0;
  spec.tallies = TallyRequest{false, false, false, true, false, estimator};
  spec.grid.rho = UniformAxis{0.0, 10.0, 100};
  // About 2e6 scattering events at every albedo.
  spec.run.photons = static_cast<std::uint64_t>(2e6 * (1.0 - albedo)) + 20000;
  spec.run.batches = 40;
  spec.run.threads = 2;
  const TransportOutput out = run_infinite_medium(spec);
  const TallyResult& fluence = testing::find_tally(out, "fluence_spherical");

  // Shells [0.1, 10] (the first, [0, 0.1), holds the 1/rho^2 singularity and is left out):
  // each within 5 sigma, and the mean squared z-score near 1.
  double sum_z2 = 0.0;
  int used = 0;
  for (int i = 1; i < spec.grid.rho.bins; ++i) {
    const double exact = point_source_fluence_shell_average(albedo, spec.grid.rho.edge(i),
                                                            spec.grid.rho.edge(i + 1));
    // Compare only where the batch statistics are near Gaussian: shells that expect at least
    // 100 collisions (collisions = fluence x volume x photons with sigma_t = 1). Beyond, at low
    // albedo, a handful of photons carry the whole score and the batch error is unreliable.
    const double a = spec.grid.rho.edge(i), b = spec.grid.rho.edge(i + 1);
    const double volume = 4.0 / 3.0 * 3.141592653589793 * (b * b * b - a * a * a);
    if (exact * volume * static_cast<double>(spec.run.photons) < 100.0) continue;
    const double sigma = fluence.stderr_of_mean[static_cast<std::size_t>(i)];
    ASSERT_GT(sigma, 0.0) << "shell " << i;
    const double z = (fluence.mean[static_cast<std::size_t>(i)] - exact) / sigma;
    EXPECT_LT(std::abs(z), 5.0) << "shell " << i << " exact " << exact;
    sum_z2 += z * z;
    ++used;
  }
  ASSERT_GT(used, 20);
  // A collision scores one shell, so shells are nearly independent and the mean squared
  // z-score is 1 +- ~0.15. One track-length flight scores a run of neighbouring shells, whose
  // errors are then strongly correlated (runs of z ~ +2 over ten shells are common), so only a
  // loose bound on the mean applies there.
  if (estimator == Estimator::collision) {
    EXPECT_NEAR(sum_z2 / used, 1.0, 0.5);
  } else {
    EXPECT_LT(sum_z2 / used, 4.0);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Albedos, PointSourceTest,
    ::testing::Combine(::testing::Values(0.01, 0.3, 0.7, 0.9, 0.99),
                       ::testing::Values(Estimator::collision, Estimator::track_length)),
    [](const auto& param_info) {
      return "albedo_" + std::to_string(static_cast<int>(std::get<0>(param_info.param) * 100)) +
             "_" + to_string(std::get<1>(param_info.param));
    });

}  // namespace
}  // namespace scatterlab
