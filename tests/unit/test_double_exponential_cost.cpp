// The double-exponential family's hand-written Jacobian (fit/double_exponential_cost.hpp):
// its residuals against the models' own bin averages (lobe_model.hpp, an independent code
// path), and its Jacobian against the derivatives of those averages in Ceres Jets, on every
// instruction set the bin averages (fit/lobe_bin_average.hpp) are compiled for.
#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../../fit/double_exponential_cost.hpp"
#include "../physics/lobe_fixtures.hpp"
#include "every_target.hpp"

namespace scatterlab {
namespace {

using fit::LobeModel;
using testing::angular_grid;
using testing::direction;
using testing::on_every_target;
using testing::parameters;

struct Case {
  LobeModel model;
  fit::LobeParameters parameters;
};

std::vector<Case> cases() {
  fit::LobeParameters ridge = parameters(direction(0.4, 0.1), {-2.0, -6.0, 1.5, -0.7});
  ridge.ridge = {0.3, 0.85, 0.7, 0.35, 0.08, 0.05, 12.0};
  fit::LobeParameters two = ridge;
  two.second_axis = direction(0.9, 0.3);
  two.second_shape = {-3.0, -2.5, 0.8, 0.6};
  return {{LobeModel::dexp, parameters(direction(0.6, 0.0), {-1.0, -8.0, -2.0, 0.0})},
          {LobeModel::dexp, parameters(direction(2.0, 0.4), {3.0, -2.0, 1e-8, 0.0})},
          {LobeModel::adexp, parameters(direction(0.3, -0.2), {-1.0, -8.0, -2.0, -1.2})},
          {LobeModel::adexp, parameters(direction(1.2, 0.5), {0.5, -3.0, 0.4, 0.9})},
          {LobeModel::adexp_ridge, ridge},
          {LobeModel::adexp2_ridge, two}};
}

// Observations of a noisy lobe near (not at) the parameters, so that residuals are not 0.
fit::LobeObservations observations(const Case& c, const fit::LobeGrid& grid) {
  fit::LobeParameters truth = c.parameters;
  truth.shape[0] += 0.2;
  truth.axis = (truth.axis + Eigen::Vector3d(0.05, 0.02, 0.0)).normalized();
  const testing::SyntheticLobe lobe = testing::synthesize(c.model, truth, grid, 0.05, 3);
  return fit::observe(grid, lobe.data(), {});
}

TEST(DoubleExponentialCost, ResidualsAreTheModelsBinAveragesAgainstTheTally) {
  for (const bool folded : {false, true}) {
    const fit::LobeGrid grid = angular_grid(18, folded ? 18 : 36, 3, folded);
    for (const Case& c : cases()) {
      const fit::LobeObservations o = observations(c, grid);
      const fit::DoubleExponentialCost cost(grid, o, c.model);
      fit::LobeParameters p = c.parameters;
      const double* blocks[5] = {p.axis.data(), p.shape.data(), p.ridge.data(),
                                 p.second_axis.data(), p.second_shape.data()};
      on_every_target([&] {
        std::vector<double> residuals(grid.size());
        ASSERT_TRUE(cost.Evaluate(blocks, residuals.data(), nullptr));
        for (std::size_t i = 0; i < grid.size(); ++i) {
          const double model = std::exp(fit::log_bin_average(c.model, grid, i, p));
          const double expected = (model - o.radiance[i]) / o.sigma[i];
          EXPECT_NEAR(residuals[i], expected, 1e-10 * (1.0 + std::abs(expected)))
              << fit::to_string(c.model) << " bin " << i;
        }
      });
    }
  }
}

using Jet = ceres::Jet<double, 21>;  // d/d(axis, shape, ridge, second axis, second shape)

// The residuals in Jets through the models as lobe_model.hpp writes them: the reference the
// hand-written Jacobian is held against.
std::vector<Jet> autodiff_residuals(const Case& c, const fit::LobeGrid& grid,
                                    const fit::LobeObservations& o) {
  Jet axis[3], shape[4], ridge[7], second_axis[3], second_shape[4];
  for (int k = 0; k < 3; ++k) axis[k] = Jet(c.parameters.axis[k], k);
  for (int k = 0; k < 4; ++k) shape[k] = Jet(c.parameters.shape[k], 3 + k);
  for (int k = 0; k < 7; ++k) ridge[k] = Jet(c.parameters.ridge[k], 7 + k);
  for (int k = 0; k < 3; ++k) second_axis[k] = Jet(c.parameters.second_axis[k], 14 + k);
  for (int k = 0; k < 4; ++k) second_shape[k] = Jet(c.parameters.second_shape[k], 17 + k);
  const fit::DoubleExponential::Evaluator<Jet> dexp(axis, shape);
  const fit::AnisotropicRidge::Evaluator<Jet> adexp_ridge(axis, shape, ridge, grid);
  const fit::TwoLobeRidge::Evaluator<Jet> adexp2_ridge(axis, shape, ridge, grid, second_axis,
                                                       second_shape);
  std::vector<Jet> residuals;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    Jet value(0.0);
    for (const fit::LobeNode& node : grid.nodes(i)) {
      const Jet log_value = c.model == LobeModel::dexp ? dexp.log_value(node.direction)
                            : c.model == LobeModel::adexp2_ridge
                                ? adexp2_ridge.log_value(node.direction)
                                : adexp_ridge.log_value(node.direction);
      value += node.weight * exp(log_value);
    }
    if (c.model == LobeModel::adexp_ridge || c.model == LobeModel::adexp2_ridge) {
      for (const fit::RidgeNode& node : grid.ridge_nodes(i))
        value += node.weight * adexp_ridge.ridge_density(node.theta);
      value += adexp_ridge.spread_average(i / grid.phi_bins(), i % grid.phi_bins());
    }
    residuals.push_back((value - o.radiance[i]) / o.sigma[i]);
  }
  return residuals;
}

TEST(DoubleExponentialCost, JacobianIsTheModelsDerivative) {
  for (const bool folded : {false, true}) {
    const fit::LobeGrid grid = angular_grid(18, folded ? 18 : 36, 3, folded);
    for (const Case& c : cases()) {
      const fit::LobeObservations o = observations(c, grid);
      const fit::DoubleExponentialCost cost(grid, o, c.model);
      const std::vector<int>& sizes = cost.parameter_block_sizes();
      fit::LobeParameters p = c.parameters;
      const double* blocks[5] = {p.axis.data(), p.shape.data(), p.ridge.data(),
                                 p.second_axis.data(), p.second_shape.data()};
      std::vector<double> residuals(grid.size());
      std::vector<std::vector<double>> jacobian(sizes.size());
      std::vector<double*> rows;
      for (std::size_t b = 0; b < sizes.size(); ++b) {
        jacobian[b].resize(grid.size() * static_cast<std::size_t>(sizes[b]));
        rows.push_back(jacobian[b].data());
      }
      const std::vector<Jet> reference = autodiff_residuals(c, grid, o);
      on_every_target([&] {
        ASSERT_TRUE(cost.Evaluate(blocks, residuals.data(), rows.data()));
        // The axis moves on the sphere (a Ceres SphereManifold): only the derivative across p
        // counts, and the written forms of the models differ along p (dexp uses |w - p|^2 where
        // the cost uses u^2 + v^2 + rho^2, equal for unit p only).
        const Eigen::Matrix3d tangent = Eigen::Matrix3d::Identity() - p.axis * p.axis.transpose();
        const int offsets[5] = {0, 3, 7, 14, 17};
        const Eigen::Matrix3d second_tangent =
            Eigen::Matrix3d::Identity() - p.second_axis * p.second_axis.transpose();
        for (std::size_t i = 0; i < grid.size(); ++i) {
          Eigen::VectorXd expected = reference[i].v;
          expected.head<3>() = tangent * expected.head<3>();
          expected.segment<3>(14) = second_tangent * expected.segment<3>(14);
          Eigen::Vector3d axis_row(jacobian[0].data() + 3 * i);
          axis_row = tangent * axis_row;
          Eigen::Vector3d second_axis_row = Eigen::Vector3d::Zero();
          if (sizes.size() > 3) {
            second_axis_row = second_tangent * Eigen::Vector3d(jacobian[3].data() + 3 * i);
          }
          const double scale = expected.cwiseAbs().maxCoeff();
          for (std::size_t b = 0; b < sizes.size(); ++b) {
            for (int k = 0; k < sizes[b]; ++k) {
              const double value = b == 0   ? axis_row[k]
                                   : b == 3 ? second_axis_row[k]
                                            : jacobian[b][i * static_cast<std::size_t>(sizes[b]) +
                                                          static_cast<std::size_t>(k)];
              EXPECT_NEAR(value, expected[offsets[b] + k], 1e-9 * scale + 1e-12)
                  << fit::to_string(c.model) << (folded ? " folded" : "") << " bin " << i
                  << " block " << b << " column " << k;
            }
          }
        }
      });
    }
  }
}

// Where a trial step takes the lobe so steep that its bins' scale e^{largest} underflows to 0
// while the sums of its gradient overflow (gamma near its bound, b near 0: a point a fit of the
// 1e8-photon beam reached), the bins add nothing and neither do their derivatives: the
// Jacobian is 0 there, not NaN (0 inf), which would end the solve at a point it had accepted.
TEST(DoubleExponentialCost, AVanishedLobeHasAZeroJacobianNotNaN) {
  const fit::LobeGrid grid = angular_grid(18, 36, 3);
  const Case steep{LobeModel::adexp,
                   parameters(direction(0.3, 0.2), {-1.7, -4.4e-11, 48.97, -6.55})};
  const fit::LobeObservations o = observations({LobeModel::adexp, cases()[2].parameters}, grid);
  const fit::DoubleExponentialCost cost(grid, o, LobeModel::adexp);
  fit::LobeParameters p = steep.parameters;
  const double* blocks[2] = {p.axis.data(), p.shape.data()};
  std::vector<double> residuals(grid.size()), axis_rows(3 * grid.size()),
      shape_rows(4 * grid.size());
  double* rows[2] = {axis_rows.data(), shape_rows.data()};
  on_every_target([&] {
    ASSERT_TRUE(cost.Evaluate(blocks, residuals.data(), rows));
    std::size_t vanished = 0;
    for (std::size_t i = 0; i < grid.size(); ++i) {
      for (int k = 0; k < 4; ++k) EXPECT_TRUE(std::isfinite(shape_rows[4 * i + k])) << i;
      for (int k = 0; k < 3; ++k) EXPECT_TRUE(std::isfinite(axis_rows[3 * i + k])) << i;
      // The models' own average (lobe_model.hpp) is NaN where every node's l is -infinity
      // (-inf - -inf); where it is finite, the residual is its.
      const double model = std::exp(fit::log_bin_average(LobeModel::adexp, grid, i, p));
      if (std::isfinite(model)) {
        EXPECT_NEAR(residuals[i], (model - o.radiance[i]) / o.sigma[i], 1e-10) << "bin " << i;
      }
      vanished += !(model > 0.0);
    }
    EXPECT_GT(vanished, 0u);
  });
}

TEST(DoubleExponentialCost, OtherModelsAreRefused) {
  const fit::LobeGrid grid = angular_grid(18, 36, 1);
  const fit::LobeObservations o;
  EXPECT_THROW(fit::DoubleExponentialCost(grid, o, LobeModel::sg), std::invalid_argument);
  EXPECT_THROW(fit::DoubleExponentialCost(grid, o, LobeModel::asg), std::invalid_argument);
}

}  // namespace
}  // namespace scatterlab
