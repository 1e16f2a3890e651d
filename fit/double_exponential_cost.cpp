#include "double_exponential_cost.hpp"

#include <ceres/jet.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
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

// One smooth lobe at one parameter set: its axis, tangents (with their 3 x 3 Jacobians in p,
// from Jets) and shape, computed once per evaluation.
struct Lobe {
  Lobe(const double* p, const double* shape, bool anisotropic)
      : axis(p[0], p[1], p[2]),
        a(shape[0]),
        b(shape[1]),
        gamma(shape[2]),
        along_scale(0.5 * std::exp(anisotropic ? shape[3] : 0.0)),
        across_scale(0.5 * std::exp(anisotropic ? -shape[3] : 0.0)) {
    const Jet3 axis_jet[3] = {Jet3(p[0], 0), Jet3(p[1], 1), Jet3(p[2], 2)};
    detail::symmetry_tangents(axis_jet, t1_jet, t2_jet);
    t1 = {t1_jet[0].a, t1_jet[1].a, t1_jet[2].a};
    t2 = {t2_jet[0].a, t2_jet[1].a, t2_jet[2].a};
  }
  Eigen::Vector3d axis, t1, t2;
  Jet3 t1_jet[3], t2_jet[3];
  double a, b, gamma, along_scale, across_scale;
};

// A lobe's average over one bin, sum_q w_q e^{l_q} = e^{largest} sum, and the gradient of
// `sum` in the intermediates (b, gamma, A, B, t1, t2, p; the header's order).
struct BinAverage {
  double largest = 0.0, sum = 0.0;
  std::array<double, 4> scalar{};
  Eigen::Vector3d d_t1 = Eigen::Vector3d::Zero(), d_t2 = Eigen::Vector3d::Zero(),
                  d_p = Eigen::Vector3d::Zero();
};

BinAverage average(const Lobe& lobe, std::span<const LobeNode> nodes, bool want_jacobian,
                   std::array<NodeTerms, kMaxNodes>& terms) {
  BinAverage m;
  m.largest = -std::numeric_limits<double>::infinity();
  for (std::size_t q = 0; q < nodes.size(); ++q) {
    const Eigen::Vector3d& w = nodes[q].direction;
    NodeTerms& t = terms[q];
    t.u = lobe.t1.dot(w);
    t.v = lobe.t2.dot(w);
    t.rho = 1.0 - lobe.axis.dot(w);
    const double s2 =
        lobe.along_scale * t.u * t.u + lobe.across_scale * t.v * t.v + 0.5 * t.rho * t.rho;
    t.s = s2 > 0.0 ? std::sqrt(s2) : 0.0;
    ramp(lobe.gamma, t);
    t.log_value = lobe.a + lobe.b * t.ramp;
    m.largest = std::max(m.largest, t.log_value);
  }
  for (std::size_t q = 0; q < nodes.size(); ++q) {
    const NodeTerms& t = terms[q];
    const double weight = nodes[q].weight * std::exp(t.log_value - m.largest);
    m.sum += weight;
    if (!want_jacobian) continue;
    const double g = t.s > 0.0 ? weight * lobe.b * t.growth / (2.0 * t.s) : 0.0;
    m.scalar[0] += weight * t.ramp;
    m.scalar[1] += weight * lobe.b * t.ramp_gamma;
    m.scalar[2] += g * t.u * t.u;
    m.scalar[3] += g * t.v * t.v;
    m.d_t1 += (2.0 * g * lobe.along_scale * t.u) * nodes[q].direction;
    m.d_t2 += (2.0 * g * lobe.across_scale * t.v) * nodes[q].direction;
    m.d_p -= (g * t.rho) * nodes[q].direction;
  }
  return m;
}

// The rows of a lobe's axis and shape blocks for one residual, `factor` = e^{largest} / sigma
// (the a-derivative is `sum` times it; `extra_a` adds the ridge's). false where not finite.
bool write_rows(const Lobe& lobe, const BinAverage& m, double factor, double extra_a,
                int shape_size, double* axis_row, double* shape_row) {
  if (axis_row) {
    for (int c = 0; c < 3; ++c) {
      double value = m.d_p[c];
      for (int k = 0; k < 3; ++k) {
        value += m.d_t1[k] * lobe.t1_jet[k].v[c] + m.d_t2[k] * lobe.t2_jet[k].v[c];
      }
      axis_row[c] = factor * value;
    }
    if (!all_finite(axis_row, 3)) return false;
  }
  if (shape_row) {
    shape_row[0] = factor * m.sum + extra_a;
    shape_row[1] = factor * m.scalar[0];
    shape_row[2] = factor * m.scalar[1];
    if (shape_size == AnisotropicDoubleExponential::kShape) {
      // dA/deta = A, dB/deta = -B
      shape_row[3] = factor * (m.scalar[2] * lobe.along_scale - m.scalar[3] * lobe.across_scale);
    }
    if (!all_finite(shape_row, shape_size)) return false;
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
      with_ridge_(model == LobeModel::adexp_ridge || model == LobeModel::adexp2_ridge),
      two_lobes_(model == LobeModel::adexp2_ridge) {
  if (model != LobeModel::dexp && model != LobeModel::dexp_paper && model != LobeModel::adexp &&
      !with_ridge_) {
    throw std::invalid_argument("DoubleExponentialCost: not a double-exponential model");
  }
  if (grid.nodes_per_bin() > kMaxNodes) {
    throw std::invalid_argument("DoubleExponentialCost: more nodes per bin than order 8 gives");
  }
  set_num_residuals(static_cast<int>(observations.radiance.size()));
  mutable_parameter_block_sizes()->push_back(3);
  mutable_parameter_block_sizes()->push_back(shape_size_);
  if (with_ridge_) mutable_parameter_block_sizes()->push_back(AnisotropicRidge::kRidge);
  if (two_lobes_) {
    mutable_parameter_block_sizes()->push_back(3);
    mutable_parameter_block_sizes()->push_back(shape_size_);
  }
}

bool DoubleExponentialCost::Evaluate(double const* const* parameters, double* residuals,
                                     double** jacobians) const {
  const bool anisotropic = shape_size_ == AnisotropicDoubleExponential::kShape;
  const Lobe first(parameters[0], parameters[1], anisotropic);
  std::optional<Lobe> second;
  if (two_lobes_) second.emplace(parameters[3], parameters[4], anisotropic);

  // The ridge in Jets over (a, c, g, k, theta_on, width, c_spread, kappa); the smooth part of
  // this Evaluator is not used.
  Jet8 axis8[3], shape8[AnisotropicDoubleExponential::kShape], ridge8[kRidge];
  // (a unique_ptr: GCC 12 sees an optional's vectors as maybe uninitialized)
  std::unique_ptr<AnisotropicRidge::Evaluator<Jet8>> ridge;
  if (with_ridge_) {
    for (int k = 0; k < 3; ++k) axis8[k] = Jet8(parameters[0][k]);
    for (int k = 0; k < shape_size_; ++k) shape8[k] = Jet8(parameters[1][k]);
    shape8[0] = Jet8(first.a, 0);
    for (int k = 0; k < kRidge; ++k) ridge8[k] = Jet8(parameters[2][k], 1 + k);
    ridge = std::make_unique<AnisotropicRidge::Evaluator<Jet8>>(axis8, shape8, ridge8, grid_);
  }

  const LobeObservations& o = observations_;
  const bool want_jacobian = jacobians != nullptr;
  const auto row = [&](int block, std::size_t i, int size) -> double* {
    return want_jacobian && jacobians[block] ? jacobians[block] + static_cast<std::size_t>(size) * i
                                             : nullptr;
  };
  std::array<NodeTerms, kMaxNodes> terms;
  for (std::size_t i = 0; i < o.radiance.size(); ++i) {
    const std::span<const LobeNode> nodes = grid_.nodes(i);
    const BinAverage m1 = average(first, nodes, want_jacobian, terms);
    std::optional<BinAverage> m2;
    if (second) m2 = average(*second, nodes, want_jacobian, terms);
    Jet8 extra(0.0);
    if (ridge) {
      for (const RidgeNode& node : grid_.ridge_nodes(i)) {
        extra += node.weight * ridge->ridge_density(node.theta);
      }
      extra += ridge->spread_average(i / grid_.phi_bins(), i % grid_.phi_bins());
    }
    const double inverse_sigma = 1.0 / o.sigma[i];
    const double scale1 = std::exp(m1.largest), scale2 = m2 ? std::exp(m2->largest) : 0.0;
    const double model = scale1 * m1.sum + (m2 ? scale2 * m2->sum : 0.0) + extra.a;
    residuals[i] = (model - o.radiance[i]) * inverse_sigma;
    if (!std::isfinite(residuals[i])) return false;
    if (!want_jacobian) continue;

    if (!write_rows(first, m1, scale1 * inverse_sigma, extra.v[0] * inverse_sigma, shape_size_,
                    row(0, i, 3), row(1, i, shape_size_))) {
      return false;
    }
    if (double* ridge_row = with_ridge_ ? row(2, i, kRidge) : nullptr) {
      for (int k = 0; k < kRidge; ++k) ridge_row[k] = extra.v[1 + k] * inverse_sigma;
      if (!all_finite(ridge_row, kRidge)) return false;
    }
    if (m2 && !write_rows(*second, *m2, scale2 * inverse_sigma, 0.0, shape_size_, row(3, i, 3),
                          row(4, i, shape_size_))) {
      return false;
    }
  }
  return true;
}

}  // namespace scatterlab::fit
