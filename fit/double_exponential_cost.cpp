#include "double_exponential_cost.hpp"

#include <ceres/jet.h>

#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>

#include "scatterlab/fit/lobe_model.hpp"

namespace scatterlab::fit {

namespace {

using Jet3 = ceres::Jet<double, 3>;  // d/dp
constexpr int kRidge = AnisotropicRidge::kRidge;
using Jet8 = ceres::Jet<double, 1 + kRidge>;  // d/d(a, ridge)

// One smooth lobe at one parameter set: its axis, tangents (with their 3 x 3 Jacobians in p,
// from Jets) and shape, computed once per evaluation.
struct Lobe {
  Lobe(const double* p, const double* shape, bool anisotropic) {
    const Jet3 axis_jet[3] = {Jet3(p[0], 0), Jet3(p[1], 1), Jet3(p[2], 2)};
    detail::symmetry_tangents(axis_jet, t1_jet, t2_jet);
    terms.axis = {p[0], p[1], p[2]};
    terms.t1 = {t1_jet[0].a, t1_jet[1].a, t1_jet[2].a};
    terms.t2 = {t2_jet[0].a, t2_jet[1].a, t2_jet[2].a};
    terms.a = shape[0];
    terms.b = shape[1];
    terms.gamma = shape[2];
    terms.along_scale = 0.5 * std::exp(anisotropic ? shape[3] : 0.0);
    terms.across_scale = 0.5 * std::exp(anisotropic ? -shape[3] : 0.0);
  }
  LobeTerms terms;
  Jet3 t1_jet[3], t2_jet[3];
};

bool all_finite(const double* values, int count) {
  for (int i = 0; i < count; ++i) {
    if (!std::isfinite(values[i])) return false;
  }
  return true;
}

// The rows of a lobe's axis and shape blocks for residual i, `factor` = scale / sigma
// (the a-derivative is `sum` times it; `extra_a` adds the ridge's). A lobe whose scale
// underflowed to 0 (its largest l below about -745) adds nothing to the bin, and nothing to the
// derivatives either: e^{largest} times sums that may have overflowed tends to 0. false where
// not finite.
bool write_rows(const Lobe& lobe, const BinAverages& m, std::size_t i, double factor,
                double extra_a, int shape_size, double* axis_row, double* shape_row) {
  if (axis_row) {
    for (int c = 0; c < 3; ++c) {
      double value = m.d_p[c][i];
      for (int k = 0; k < 3; ++k) {
        value += m.d_t1[k][i] * lobe.t1_jet[k].v[c] + m.d_t2[k][i] * lobe.t2_jet[k].v[c];
      }
      axis_row[c] = factor == 0.0 ? 0.0 : factor * value;
    }
    if (!all_finite(axis_row, 3)) return false;
  }
  if (shape_row) {
    for (int k = 0; k < shape_size; ++k) shape_row[k] = 0.0;
    shape_row[0] = extra_a;
    if (factor != 0.0) {
      shape_row[0] += factor * m.sum[i];
      shape_row[1] = factor * m.ramp[i];
      shape_row[2] = factor * m.ramp_gamma[i];
      if (shape_size == AnisotropicDoubleExponential::kShape) {
        // dA/deta = A, dB/deta = -B
        shape_row[3] =
            factor * (m.along[i] * lobe.terms.along_scale - m.across[i] * lobe.terms.across_scale);
      }
    }
    if (!all_finite(shape_row, shape_size)) return false;
  }
  return true;
}

}  // namespace

DoubleExponentialCost::DoubleExponentialCost(const LobeGrid& grid,
                                             const LobeObservations& observations, LobeModel model)
    : grid_(grid),
      nodes_(grid),
      observations_(observations),
      shape_size_(model == LobeModel::dexp || model == LobeModel::dexp_paper
                      ? DoubleExponential::kShape
                      : AnisotropicDoubleExponential::kShape),
      with_ridge_(model == LobeModel::adexp_ridge || model == LobeModel::adexp2_ridge),
      two_lobes_(model == LobeModel::adexp2_ridge) {
  if (!serves(model)) {
    throw std::invalid_argument("DoubleExponentialCost: not a double-exponential model");
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
    shape8[0] = Jet8(first.terms.a, 0);
    for (int k = 0; k < kRidge; ++k) ridge8[k] = Jet8(parameters[2][k], 1 + k);
    ridge = std::make_unique<AnisotropicRidge::Evaluator<Jet8>>(axis8, shape8, ridge8, grid_);
  }

  const LobeObservations& o = observations_;
  const bool want_jacobian = jacobians != nullptr;
  const auto row = [&](int block, std::size_t i, int size) -> double* {
    return want_jacobian && jacobians[block] ? jacobians[block] + static_cast<std::size_t>(size) * i
                                             : nullptr;
  };
  // Every bin's averages at once (lobe_bin_average.hpp), into this thread's buffers.
  thread_local BinAverages m1, m2;
  average_over_bins(first.terms, nodes_, want_jacobian, m1);
  if (second) average_over_bins(second->terms, nodes_, want_jacobian, m2);
  for (std::size_t i = 0; i < o.radiance.size(); ++i) {
    Jet8 extra(0.0);
    if (ridge) {
      for (const RidgeNode& node : grid_.ridge_nodes(i)) {
        extra += node.weight * ridge->ridge_density(node.theta);
      }
      extra += ridge->spread_average(i / grid_.phi_bins(), i % grid_.phi_bins());
    }
    const double inverse_sigma = 1.0 / o.sigma[i];
    const double scale1 = m1.scale[i], scale2 = second ? m2.scale[i] : 0.0;
    const double model = scale1 * m1.sum[i] + (second ? scale2 * m2.sum[i] : 0.0) + extra.a;
    residuals[i] = (model - o.radiance[i]) * inverse_sigma;
    if (!std::isfinite(residuals[i])) return false;
    if (!want_jacobian) continue;

    if (!write_rows(first, m1, i, scale1 * inverse_sigma, extra.v[0] * inverse_sigma, shape_size_,
                    row(0, i, 3), row(1, i, shape_size_))) {
      return false;
    }
    if (double* ridge_row = with_ridge_ ? row(2, i, kRidge) : nullptr) {
      for (int k = 0; k < kRidge; ++k) ridge_row[k] = extra.v[1 + k] * inverse_sigma;
      if (!all_finite(ridge_row, kRidge)) return false;
    }
    if (second && !write_rows(*second, m2, i, scale2 * inverse_sigma, 0.0, shape_size_,
                              row(3, i, 3), row(4, i, shape_size_))) {
      return false;
    }
  }
  return true;
}

}  // namespace scatterlab::fit
