#include "double_exponential_cost.hpp"

#include <ceres/jet.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "scatterlab/fit/lobe_model.hpp"

namespace scatterlab::fit {

namespace {

using Jet3 = ceres::Jet<double, 3>;  // d/dp
constexpr int kRidge = AnisotropicRidge::kRidge;
using Jet8 = ceres::Jet<double, 1 + kRidge>;  // d/d(a, ridge)

constexpr std::size_t kMaxNodes = 2 * 8 * 8;  // a folded grid's bin at quadrature order 8

// The smooth lobe at one node, and what its gradient needs (see the header).
struct NodeTerms {
  double log_value, u, v, rho, s, ramp, ramp_gamma, growth;  // growth = e^{gamma s}
};

// R = (e^{x} - 1) / gamma and dR/dgamma = (x e^{x} - (e^{x} - 1)) / gamma^2 with x = gamma s,
// each by its series where the closed form cancels: R as lobe_model.hpp's exp_ramp, and
// dR/dgamma = s^2 sum_{n >= 2} (n - 1) x^{n-2} / n! = s^2 (1/2 + x/3 + x^2/8 + x^3/30 + ...),
// whose next term, x^4/144, is below 1e-14 for |x| < 1e-3.
void ramp(double gamma, NodeTerms& t) {
  const double x = gamma * t.s, grown = std::expm1(x);
  t.growth = grown + 1.0;
  t.ramp = std::abs(gamma) > 1e-6 ? grown / gamma : t.s * (1.0 + x * (0.5 + x / 6.0));
  t.ramp_gamma = std::abs(x) < 1e-3 ? t.s * t.s * (0.5 + x * (1.0 / 3.0 + x * (0.125 + x / 30.0)))
                                    : (x * t.growth - grown) / (gamma * gamma);
}

bool all_finite(const double* values, int count) {
  for (int i = 0; i < count; ++i) {
    if (!std::isfinite(values[i])) return false;
  }
  return true;
}

}  // namespace

DoubleExponentialCost::DoubleExponentialCost(const LobeGrid& grid,
                                             const LobeObservations& observations, LobeModel model)
    : grid_(grid),
      observations_(observations),
      shape_size_(model == LobeModel::dexp || model == LobeModel::dexp_paper
                      ? DoubleExponential::kShape
                      : AnisotropicDoubleExponential::kShape),
      with_ridge_(model == LobeModel::adexp_ridge) {
  if (model != LobeModel::dexp && model != LobeModel::dexp_paper && model != LobeModel::adexp &&
      model != LobeModel::adexp_ridge) {
    throw std::invalid_argument("DoubleExponentialCost: not a double-exponential model");
  }
  if (grid.nodes_per_bin() > kMaxNodes) {
    throw std::invalid_argument("DoubleExponentialCost: more nodes per bin than order 8 gives");
  }
  set_num_residuals(static_cast<int>(observations.radiance.size()));
  mutable_parameter_block_sizes()->push_back(3);
  mutable_parameter_block_sizes()->push_back(shape_size_);
  if (with_ridge_) mutable_parameter_block_sizes()->push_back(AnisotropicRidge::kRidge);
}

bool DoubleExponentialCost::Evaluate(double const* const* parameters, double* residuals,
                                     double** jacobians) const {
  const double* p = parameters[0];
  const double* shape = parameters[1];
  const double a = shape[0], b = shape[1], gamma = shape[2];
  const double eta = shape_size_ == AnisotropicDoubleExponential::kShape ? shape[3] : 0.0;
  const double along_scale = 0.5 * std::exp(eta), across_scale = 0.5 * std::exp(-eta);

  // The tangents and their 3 x 3 Jacobians in p, once per evaluation.
  const Jet3 axis_jet[3] = {Jet3(p[0], 0), Jet3(p[1], 1), Jet3(p[2], 2)};
  Jet3 t1_jet[3], t2_jet[3];
  detail::symmetry_tangents(axis_jet, t1_jet, t2_jet);
  const Eigen::Vector3d axis(p[0], p[1], p[2]);
  const Eigen::Vector3d t1(t1_jet[0].a, t1_jet[1].a, t1_jet[2].a);
  const Eigen::Vector3d t2(t2_jet[0].a, t2_jet[1].a, t2_jet[2].a);

  // The ridge in Jets over (a, c, g, k, theta_on, width, c_spread, kappa); the smooth part of
  // this Evaluator is not used.
  Jet8 axis8[3], shape8[AnisotropicDoubleExponential::kShape], ridge8[kRidge];
  std::optional<AnisotropicRidge::Evaluator<Jet8>> ridge;
  if (with_ridge_) {
    for (int k = 0; k < 3; ++k) axis8[k] = Jet8(p[k]);
    for (int k = 0; k < shape_size_; ++k) shape8[k] = Jet8(shape[k]);
    shape8[0] = Jet8(a, 0);
    for (int k = 0; k < kRidge; ++k) ridge8[k] = Jet8(parameters[2][k], 1 + k);
    ridge.emplace(axis8, shape8, ridge8, grid_);
  }

  const LobeObservations& o = observations_;
  const bool want_jacobian = jacobians != nullptr;
  std::array<NodeTerms, kMaxNodes> terms;
  for (std::size_t i = 0; i < o.radiance.size(); ++i) {
    // The bin average sum_q w_q e^{l_q}, relative to the largest l_q.
    const std::span<const LobeNode> nodes = grid_.nodes(i);
    double largest = -std::numeric_limits<double>::infinity();
    for (std::size_t q = 0; q < nodes.size(); ++q) {
      const Eigen::Vector3d& w = nodes[q].direction;
      NodeTerms& t = terms[q];
      t.u = t1.dot(w);
      t.v = t2.dot(w);
      t.rho = 1.0 - axis.dot(w);
      const double s2 = along_scale * t.u * t.u + across_scale * t.v * t.v + 0.5 * t.rho * t.rho;
      t.s = s2 > 0.0 ? std::sqrt(s2) : 0.0;
      ramp(gamma, t);
      t.log_value = a + b * t.ramp;
      largest = std::max(largest, t.log_value);
    }
    // The sum, which is also its a-derivative, and its gradient in the other intermediates
    // (b, gamma, A, B, t1, t2, p; the header's order).
    double sum = 0.0;
    std::array<double, 4> scalar{};
    Eigen::Vector3d d_t1 = Eigen::Vector3d::Zero(), d_t2 = d_t1, d_p = d_t1;
    for (std::size_t q = 0; q < nodes.size(); ++q) {
      const NodeTerms& t = terms[q];
      const double weight = nodes[q].weight * std::exp(t.log_value - largest);
      sum += weight;
      if (!want_jacobian) continue;
      const double g = t.s > 0.0 ? weight * b * t.growth / (2.0 * t.s) : 0.0;
      scalar[0] += weight * t.ramp;
      scalar[1] += weight * b * t.ramp_gamma;
      scalar[2] += g * t.u * t.u;
      scalar[3] += g * t.v * t.v;
      d_t1 += (2.0 * g * along_scale * t.u) * nodes[q].direction;
      d_t2 += (2.0 * g * across_scale * t.v) * nodes[q].direction;
      d_p -= (g * t.rho) * nodes[q].direction;
    }
    const double scale = std::exp(largest);
    Jet8 extra(0.0);
    if (ridge) {
      for (const RidgeNode& node : grid_.ridge_nodes(i)) {
        extra += node.weight * ridge->ridge_density(node.theta);
      }
      extra += ridge->spread_average(i / grid_.phi_bins(), i % grid_.phi_bins());
    }
    const double inverse_sigma = 1.0 / o.sigma[i];
    residuals[i] = (scale * sum + extra.a - o.radiance[i]) * inverse_sigma;
    if (!std::isfinite(residuals[i])) return false;
    if (!want_jacobian) continue;

    const double factor = scale * inverse_sigma;
    if (double* row = jacobians[0] ? jacobians[0] + 3 * i : nullptr) {
      for (int c = 0; c < 3; ++c) {
        double value = d_p[c];
        for (int k = 0; k < 3; ++k) value += d_t1[k] * t1_jet[k].v[c] + d_t2[k] * t2_jet[k].v[c];
        row[c] = factor * value;
      }
      if (!all_finite(row, 3)) return false;
    }
    if (double* row = jacobians[1] ? jacobians[1] + shape_size_ * i : nullptr) {
      row[0] = factor * sum + extra.v[0] * inverse_sigma;
      row[1] = factor * scalar[0];
      row[2] = factor * scalar[1];
      if (shape_size_ == AnisotropicDoubleExponential::kShape) {
        row[3] = factor * (scalar[2] * along_scale - scalar[3] * across_scale);  // dA/deta = A
      }
      if (!all_finite(row, shape_size_)) return false;
    }
    if (with_ridge_ && jacobians[2]) {
      double* row = jacobians[2] + kRidge * i;
      for (int k = 0; k < kRidge; ++k) row[k] = extra.v[1 + k] * inverse_sigma;
      if (!all_finite(row, kRidge)) return false;
    }
  }
  return true;
}

}  // namespace scatterlab::fit
