// The chi-square objective of the lobe fits (lobe_fit.hpp): the floor on dark directions' standard
// errors, chi^2/dof and the noise level of an exact model, the status of a fit that ends on a
// bound, the solver's log kept off stderr, the anisotropic spherical Gaussian against Xu et al.'s
// formula written out, and the ridge's bin averages against an independent integral.
#include <glog/logging.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "../physics/lobe_fixtures.hpp"
#include "scatterlab/core/random.hpp"
#include "scatterlab/fit/lobe_fit.hpp"

namespace scatterlab {
namespace {

using fit::FitStatus;
using fit::LobeModel;
using testing::angular_grid;
using testing::direction;
using testing::normal_deviate;
using testing::parameters;

constexpr double kPi = std::numbers::pi;

// A tally of events of radiance q / Omega_i each: n_i events give L = n_i q / Omega_i and
// stderr = sqrt(n_i) q / Omega_i. The floor is then exactly q / Omega_i, and a dark direction
// gets it as its sigma.
TEST(LobeObjective, DarkDirectionsAreFlooredAtOneEvent) {
  const fit::LobeGrid grid = angular_grid(18, 36, 1);
  const double q = 3e-4;
  std::vector<double> mean(grid.size()), error(grid.size());
  for (std::size_t bin = 0; bin < grid.size(); ++bin) {
    const double events = bin % 3 == 0 ? 0.0 : static_cast<double>(1 + bin % 50);
    mean[bin] = events * q / grid.solid_angle(bin);
    error[bin] = std::sqrt(events) * q / grid.solid_angle(bin);
  }
  const fit::LobeObservations o = fit::observe(grid, {mean, error, {}}, {});
  ASSERT_EQ(o.status, FitStatus::converged) << o.message;
  EXPECT_NEAR(o.event_radiance, q, 1e-12 * q);
  for (std::size_t bin = 0; bin < grid.size(); ++bin) {
    const double floor = q / grid.solid_angle(bin);
    EXPECT_NEAR(o.sigma[bin], std::max(error[bin], floor), 1e-9 * floor) << bin;
    EXPECT_EQ(o.radiance[bin], mean[bin]);  // dark directions stay in the fit
  }
}

// Data = model + sigma N(0, 1) with a Poisson-like sigma_i = sqrt(q <m>_i / Omega_i) and every
// direction well above one event: at the true parameters chi^2 is a sum of 648 squared normal
// deviates (chi^2/dof = 1 within 3 sqrt(2/648) = 0.17), the L1 error of the exact model is
// sqrt(2/pi) sum Omega sigma / sum Omega L = the reported noise (within a few percent: 648
// absolute deviates), and the fit lowers chi^2 by about its number of parameters, no more.
TEST(LobeObjective, TheTrueModelShowsChiSquarePerDofOneAndTheNoiseLevel) {
  const fit::LobeGrid grid = angular_grid(18, 36, 3);
  const auto truth =
      parameters(direction(0.6, 0.0), fit::double_exponential_shape(1.0, 2.0, -1.0, -0.5));
  const double q = 1e-4;
  std::vector<double> mean, error;
  for (std::size_t bin = 0; bin < grid.size(); ++bin) {
    const double value = std::exp(fit::log_bin_average(LobeModel::adexp, grid, bin, truth));
    const double sigma = std::sqrt(q * value / grid.solid_angle(bin));
    ASSERT_GT(value * grid.solid_angle(bin) / q, 50.0);  // at least 50 events everywhere
    PhotonRandom random(11, bin);
    mean.push_back(value + sigma * normal_deviate(random));
    error.push_back(sigma);
  }
  const fit::LobeData data{mean, error, {}};
  const fit::LobeObservations o = fit::observe(grid, data, {});
  ASSERT_EQ(o.status, FitStatus::converged);
  const fit::LobeErrors at_truth = fit::lobe_errors(LobeModel::adexp, grid, o, truth);
  EXPECT_NEAR(at_truth.chi2_dof, 1.0, 0.17);
  EXPECT_NEAR(at_truth.sphere / at_truth.noise, 1.0, 0.08);

  const fit::LobeFit fitted = fit::fit_lobe(LobeModel::adexp, grid, data, o, truth);
  ASSERT_EQ(fitted.status, FitStatus::converged) << fitted.message;
  const double dof = 648.0 - 6.0;
  const double chi2_truth = at_truth.chi2_dof * dof, chi2_fit = fitted.chi2_dof * dof;
  EXPECT_LE(chi2_fit, chi2_truth);
  EXPECT_LT(chi2_truth - chi2_fit, 30.0);  // ~ chi^2 with 6 dof: mean 6, 30 is p < 1e-4
  EXPECT_NEAR(fitted.cost, 0.5 * chi2_fit, 1e-6 * chi2_fit);
}

// eta beyond its bound: the fit converges onto eta = -8 and says so, in its status alone: once a
// fit has run, Ceres's own log lines (glog, to stderr) stay off the terminal.
TEST(LobeObjective, AFitThatEndsOnAnArtificialBoundIsAtBound) {
  const fit::LobeGrid grid = angular_grid(18, 36, 3);
  const auto truth =
      parameters(direction(0.6, 0.0), fit::double_exponential_shape(-1.0, 4.0, -2.0, -10.0));
  const testing::SyntheticLobe lobe = testing::synthesize(LobeModel::adexp, truth, grid, 0.02, 3);
  const fit::LobeObservations o = fit::observe(grid, lobe.data(), {});
  const fit::LobeFit fitted = fit::fit_lobe(LobeModel::adexp, grid, lobe.data(), o, truth);
  EXPECT_EQ(fitted.status, FitStatus::at_bound) << fitted.message;
  EXPECT_NEAR(fitted.parameters.shape[3], -fit::kEtaBound, 1e-9);
  EXPECT_TRUE(fit::usable(fitted.status));
  EXPECT_NE(fit::fit_status_legend().find("4 at_bound"), std::string::npos);
  ::testing::internal::CaptureStderr();
  LOG(ERROR) << "polynomial.cc:238] Failed to extract eigenvalues from companion matrix.";
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

// Xu et al. 2013's ASG written out for an axis in the plane of symmetry, p = (sin t, 0, cos t):
// x = (cos t, 0, -sin t) in the plane, y = e_phi across it.
TEST(LobeObjective, AnisotropicSphericalGaussianIsXuEtAlsFormula) {
  const double t = 0.7, log_c = 0.3, lambda = 5.0, mu = 40.0;
  const auto p = parameters(direction(t, 0.0), {log_c, lambda, mu, 0.0});
  const Eigen::Vector3d x(std::cos(t), 0.0, -std::sin(t)), y(0.0, 1.0, 0.0);
  for (const Eigen::Vector3d& v :
       {direction(0.5, 0.2), direction(1.2, -0.4), direction(0.7, 0.0), direction(2.0, 1.0)}) {
    const double expected = std::exp(log_c) * std::max(v.dot(p.axis), 0.0) *
                            std::exp(-lambda * v.dot(x) * v.dot(x) - mu * v.dot(y) * v.dot(y));
    EXPECT_NEAR(std::exp(fit::log_model_value(LobeModel::asg, p, v)), expected,
                1e-12 * std::exp(log_c));
  }
  // Behind the smooth term's horizon the ASG is zero.
  EXPECT_EQ(std::exp(fit::log_model_value(LobeModel::asg, p, -p.axis)), 0.0);
}

// The ridge's power over the sphere, sum Omega (<L> - <adexp>), is the integral of R(theta) over
// [0, pi] (ridge.hpp), computed here by the midpoint rule on 10^5 intervals; the folded grid gives
// the same bin averages as the unfolded one.
TEST(LobeObjective, RidgeBinAveragesHoldTheRidgesPower) {
  fit::LobeParameters p = parameters(direction(0.5, 0.0), {-30.0, -1.0, 0.0, 0.0});
  p.ridge = {2.0, 0.8, 0.6, 0.5, 0.15};
  double exact = 0.0;
  const int steps = 100000;
  for (int i = 0; i < steps; ++i) {
    const double theta = kPi * (i + 0.5) / steps;
    exact += 2.0 * std::exp(-30.0 + fit::log_ridge_profile(p.ridge.data(), theta)) * kPi / steps;
  }
  const fit::LobeGrid unfolded = angular_grid(18, 36, 8), folded = angular_grid(18, 18, 8, true);
  double power = 0.0;
  for (std::size_t bin = 0; bin < unfolded.size(); ++bin) {
    const double value = std::exp(fit::log_bin_average(LobeModel::adexp_ridge, unfolded, bin, p));
    const double lobe = std::exp(fit::log_bin_average(LobeModel::adexp, unfolded, bin, p));
    power += unfolded.solid_angle(bin) * (value - lobe);
    const std::size_t t = bin / 36, f = bin % 36;
    if (f == 0) {
      const double mirrored =
          std::exp(fit::log_bin_average(LobeModel::adexp_ridge, folded, t * 18, p));
      EXPECT_NEAR(mirrored, value, 1e-12 * value) << t;
    }
  }
  EXPECT_NEAR(power, exact, 1e-6 * exact);
}

}  // namespace
}  // namespace scatterlab
