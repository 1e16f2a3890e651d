#include "scatterlab/fit/lobe_fit.hpp"

#include <ceres/ceres.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "scatterlab/core/constants.hpp"

namespace scatterlab::fit {

namespace {

constexpr std::size_t kMaxNodesPerBin = 8 * 8 * 2;  // order 8, mirrored on a folded grid
constexpr double kGammaBound = 50.0;  // e^{50 sqrt 2}: far beyond any lobe, still finite
constexpr double kEtaBound = 8.0;     // the two tangents' widths differ by e^{8/2} ~ 55 at most

// log of the model averaged over one angular bin: log sum_q w_q exp(l_q), shifted by the
// largest l_q so that a lobe with lambda ~ 1e3 neither overflows nor underflows.
template <class Evaluator, typename T = decltype(std::declval<Evaluator>().log_value({}))>
T log_average(const LobeGrid& grid, std::size_t bin, const Evaluator& lobe) {
  using std::exp;
  using std::log;
  const std::span<const LobeNode> nodes = grid.nodes(bin);
  std::array<T, kMaxNodesPerBin> values;
  T largest = lobe.log_value(nodes[0].direction);
  values[0] = largest;
  for (std::size_t q = 1; q < nodes.size(); ++q) {
    values[q] = lobe.log_value(nodes[q].direction);
    if (values[q] > largest) largest = values[q];
  }
  T sum(0.0);
  for (std::size_t q = 0; q < nodes.size(); ++q) sum += nodes[q].weight * exp(values[q] - largest);
  return largest + log(sum);
}

// The residuals of lobe_fit.hpp: w_i (log <m>_i - log L_i), one block for the whole lobe.
template <class Model>
struct LobeResidual {
  const LobeGrid* grid;
  const LobeObservations* observations;

  template <typename T>
  bool operator()(const T* axis, const T* shape, T* residuals) const {
    const LobeObservations& o = *observations;
    const typename Model::template Evaluator<T> lobe(axis, shape);
    for (std::size_t k = 0; k < o.bins.size(); ++k) {
      residuals[k] = o.weights[k] * (log_average(*grid, o.bins[k], lobe) - o.log_radiance[k]);
    }
    return true;
  }
};

template <class Model>
double cost_of(const LobeGrid& grid, const LobeObservations& observations,
               const LobeParameters& parameters) {
  double cost = 0.0;
  const typename Model::template Evaluator<double> lobe(parameters.axis.data(),
                                                        parameters.shape.data());
  for (std::size_t k = 0; k < observations.bins.size(); ++k) {
    const double r = observations.weights[k] *
                     (log_average(grid, observations.bins[k], lobe) - observations.log_radiance[k]);
    cost += 0.5 * r * r;
  }
  return std::isfinite(cost) ? cost : std::numeric_limits<double>::infinity();
}

// Keeps a starting point inside the bounds that fit_lobe sets (Ceres refuses infeasible ones).
LobeParameters feasible(LobeModel model, LobeParameters start) {
  start.axis.normalize();
  auto& s = start.shape;
  if (model == LobeModel::sg || model == LobeModel::sg_free) s[0] = std::max(s[0], 0.0);
  if (model == LobeModel::dexp || model == LobeModel::adexp) {
    s[2] = std::clamp(s[2], -kGammaBound, kGammaBound);
  }
  if (model == LobeModel::adexp) s[3] = std::clamp(s[3], -kEtaBound, kEtaBound);
  return start;
}

template <class Model>
LobeFit solve(LobeModel model, const LobeGrid& grid, const LobeObservations& observations,
              const LobeParameters& start, const FitOptions& options) {
  LobeFit fit;
  fit.parameters = feasible(model, start);
  double* axis = fit.parameters.axis.data();
  double* shape = fit.parameters.shape.data();

  ceres::Problem problem;
  auto* cost = new ceres::AutoDiffCostFunction<LobeResidual<Model>, ceres::DYNAMIC, 3,
                                               Model::kShape>(
      new LobeResidual<Model>{&grid, &observations}, static_cast<int>(observations.bins.size()));
  problem.AddResidualBlock(cost, nullptr, axis, shape);
  if (model == LobeModel::sg) {
    problem.SetParameterBlockConstant(axis);  // p = E / |E| (Vavassori §4.2.1)
  } else {
    problem.SetManifold(axis, new ceres::SphereManifold<3>());
  }
  if (model == LobeModel::sg || model == LobeModel::sg_free) {
    problem.SetParameterLowerBound(shape, 0, 0.0);  // lambda in R+ (§4.2.1)
  } else {
    problem.SetParameterLowerBound(shape, 2, -kGammaBound);
    problem.SetParameterUpperBound(shape, 2, kGammaBound);
  }
  if (model == LobeModel::adexp) {
    problem.SetParameterLowerBound(shape, 3, -kEtaBound);
    problem.SetParameterUpperBound(shape, 3, kEtaBound);
  }

  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options.max_iterations;
  solver.function_tolerance = 1e-10;
  solver.parameter_tolerance = 1e-10;
  solver.logging_type = ceres::SILENT;
  solver.num_threads = 1;  // bins run in parallel instead
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);

  fit.parameters.axis.normalize();
  fit.cost = summary.final_cost;
  fit.iterations = static_cast<int>(summary.iterations.size());
  bool finite = std::isfinite(fit.cost) && fit.parameters.axis.allFinite();
  for (int i = 0; i < Model::kShape; ++i) finite = finite && std::isfinite(shape[i]);
  if (!finite) {
    fit.status = FitStatus::failed;
    fit.message = "non-finite parameters or cost after the solve";
  } else if (summary.termination_type == ceres::CONVERGENCE) {
    fit.status = FitStatus::converged;
  } else if (summary.termination_type == ceres::NO_CONVERGENCE) {
    fit.status = FitStatus::no_convergence;
    fit.message = summary.message;
  } else {
    fit.status = FitStatus::failed;
    fit.message = summary.message;
  }
  return fit;
}

// Solid-angle-weighted mean of log L over the directions with |p.c - target| <= half_width.
double ring_mean(const LobeGrid& grid, const LobeObservations& o, const Eigen::Vector3d& axis,
                 double target, double half_width) {
  double sum = 0.0, weight = 0.0;
  for (std::size_t k = 0; k < o.bins.size(); ++k) {
    if (std::abs(axis.dot(grid.centre(o.bins[k])) - target) <= half_width) {
      sum += grid.solid_angle(o.bins[k]) * o.log_radiance[k];
      weight += grid.solid_angle(o.bins[k]);
    }
  }
  return weight > 0.0 ? sum / weight : std::numeric_limits<double>::quiet_NaN();
}

double ring_mean_widening(const LobeGrid& grid, const LobeObservations& o,
                          const Eigen::Vector3d& axis, double target) {
  for (const double half_width : {0.1, 0.25, 0.5}) {
    const double mean = ring_mean(grid, o, axis, target, half_width);
    if (std::isfinite(mean)) return mean;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

std::string to_string(FitStatus status) {
  switch (status) {
    case FitStatus::converged: return "converged";
    case FitStatus::no_convergence: return "no_convergence";
    case FitStatus::failed: return "failed";
    case FitStatus::all_zero: return "all_zero";
    case FitStatus::too_few_directions: return "too_few_directions";
    case FitStatus::non_finite_input: return "non_finite_input";
    case FitStatus::no_axis: return "no_axis";
  }
  return "unknown";
}

std::string fit_status_legend() {
  std::string legend;
  for (const FitStatus status :
       {FitStatus::converged, FitStatus::no_convergence, FitStatus::failed, FitStatus::all_zero,
        FitStatus::too_few_directions, FitStatus::non_finite_input, FitStatus::no_axis}) {
    legend += fmt::format("{}{} {}", legend.empty() ? "" : "; ", static_cast<int>(status),
                          to_string(status));
  }
  return legend + " (0, 1: fitted; 2 and above: parameters 0, errors -1)";
}

LobeObservations observe(const LobeGrid& grid, const LobeData& data, const FitOptions& options) {
  LobeObservations o;
  bool any_radiance = false;
  double total_solid_angle = 0.0;
  for (std::size_t bin = 0; bin < grid.size(); ++bin) {
    total_solid_angle += grid.solid_angle(bin);
    const double mean = data.mean[bin], error = data.stderr_of_mean[bin];
    if (!std::isfinite(mean) || !std::isfinite(error)) {
      o.status = FitStatus::non_finite_input;
      o.message = fmt::format("non-finite radiance or stderr in direction bin (theta {}, phi {})",
                              bin / grid.phi_bins(), bin % grid.phi_bins());
      return o;
    }
    any_radiance = any_radiance || mean != 0.0;
  }
  if (!any_radiance) {
    o.status = FitStatus::all_zero;
    o.message = "no radiance in any direction";
    return o;
  }
  const double mean_solid_angle = total_solid_angle / static_cast<double>(grid.size());
  for (std::size_t bin = 0; bin < grid.size(); ++bin) {
    const double mean = data.mean[bin];
    if (!(mean > 0.0)) continue;
    const double relative = data.stderr_of_mean[bin] / mean;
    if (relative > options.max_relative_stderr) continue;
    const double floor = options.relative_stderr_floor;
    o.bins.push_back(bin);
    o.log_radiance.push_back(std::log(mean));
    o.weights.push_back(std::sqrt(grid.solid_angle(bin) / mean_solid_angle) /
                        std::sqrt(relative * relative + floor * floor));
  }
  if (o.bins.size() < options.min_directions) {
    o.status = FitStatus::too_few_directions;
    o.message = fmt::format(
        "only {} of {} directions have radiance with relative stderr <= {}; {} needed",
        o.bins.size(), grid.size(), options.max_relative_stderr, options.min_directions);
  }
  return o;
}

double fit_cost(LobeModel model, const LobeGrid& grid, const LobeObservations& observations,
                const LobeParameters& parameters) {
  const LobeParameters p = feasible(model, parameters);
  switch (model) {
    case LobeModel::sg:
    case LobeModel::sg_free: return cost_of<SphericalGaussian>(grid, observations, p);
    case LobeModel::dexp: return cost_of<DoubleExponential>(grid, observations, p);
    case LobeModel::adexp: return cost_of<AnisotropicDoubleExponential>(grid, observations, p);
  }
  return std::numeric_limits<double>::infinity();
}

LobeFit fit_lobe(LobeModel model, const LobeGrid& grid, const LobeData& data,
                 const LobeObservations& observations, const LobeParameters& start,
                 const FitOptions& options) {
  LobeFit fit;
  switch (model) {
    case LobeModel::sg:
    case LobeModel::sg_free:
      fit = solve<SphericalGaussian>(model, grid, observations, start, options);
      break;
    case LobeModel::dexp:
      fit = solve<DoubleExponential>(model, grid, observations, start, options);
      break;
    case LobeModel::adexp:
      fit = solve<AnisotropicDoubleExponential>(model, grid, observations, start, options);
      break;
  }
  if (usable(fit.status)) {
    const LobeErrors errors = lobe_errors(model, grid, data, observations, fit.parameters);
    fit.error_sphere = errors.sphere;
    fit.error_plane = errors.plane;
    fit.noise = errors.noise;
  }
  return fit;
}

LobeParameters spherical_gaussian_estimate(const LobeGrid& grid, const LobeObservations& o,
                                           const Eigen::Vector3d& axis) {
  // log L = log mu + lambda x with x = p.c - 1 (§4.2.1), weighted least squares.
  double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < o.bins.size(); ++k) {
    const double w = o.weights[k] * o.weights[k];
    const double x = axis.dot(grid.centre(o.bins[k])) - 1.0, y = o.log_radiance[k];
    sw += w, sx += w * x, sy += w * y, sxx += w * x * x, sxy += w * x * y;
  }
  LobeParameters start;
  start.axis = axis.normalized();
  const double determinant = sw * sxx - sx * sx;
  double lambda = determinant > 0.0 ? (sw * sxy - sx * sy) / determinant : 0.0;
  if (!(lambda > 0.0)) lambda = 0.0;
  start.shape[0] = lambda;
  start.shape[1] = sw > 0.0 ? (sy - lambda * sx) / sw : 0.0;
  return start;
}

LobeParameters double_exponential_estimate(const LobeGrid& grid, const LobeObservations& o) {
  // Step 1: p and M = L(p) from the brightest direction.
  std::size_t peak = 0;
  for (std::size_t k = 1; k < o.bins.size(); ++k) {
    if (o.log_radiance[k] > o.log_radiance[peak]) peak = k;
  }
  LobeParameters start;
  start.axis = grid.centre(o.bins[peak]);
  const double log_peak = o.log_radiance[peak];

  // Step 2: gamma = 2 log[(log L2 - log L1) / (log L1 - log M)] with p.w1 = 3/4, p.w2 = 0.
  // One direction each is noisy on a grid; the mean over the ring of directions is not.
  const double log_1 = ring_mean_widening(grid, o, start.axis, 0.75);
  const double log_2 = ring_mean_widening(grid, o, start.axis, 0.0);
  double gamma = 2.0 * std::log((log_2 - log_1) / (log_1 - log_peak));
  if (!std::isfinite(gamma) || gamma == 0.0) gamma = -1.0;  // no usable rings: a mild decay
  gamma = std::clamp(gamma, -kGammaBound, kGammaBound);

  // Step 3: log L - log M e^{gamma s} = log alpha (1 - e^{gamma s}), s = sqrt(1 - p.w),
  // by weighted least squares through the origin.
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t k = 0; k < o.bins.size(); ++k) {
    const double s = std::sqrt(std::max(0.0, 1.0 - start.axis.dot(grid.centre(o.bins[k]))));
    const double e = std::exp(gamma * s), w = o.weights[k] * o.weights[k];
    const double x = 1.0 - e, y = o.log_radiance[k] - log_peak * e;
    sxy += w * x * y;
    sxx += w * x * x;
  }
  const double log_alpha = sxx > 0.0 ? sxy / sxx : log_peak - 1.0;
  // Step 4: beta = log M - log alpha.
  start.shape = double_exponential_shape(log_alpha, log_peak - log_alpha, gamma);
  return start;
}

double log_bin_average(LobeModel model, const LobeGrid& grid, std::size_t bin,
                       const LobeParameters& p) {
  const double* axis = p.axis.data();
  const double* shape = p.shape.data();
  switch (model) {
    case LobeModel::sg:
    case LobeModel::sg_free:
      return log_average(grid, bin, SphericalGaussian::Evaluator<double>(axis, shape));
    case LobeModel::dexp:
      return log_average(grid, bin, DoubleExponential::Evaluator<double>(axis, shape));
    case LobeModel::adexp:
      return log_average(grid, bin, AnisotropicDoubleExponential::Evaluator<double>(axis, shape));
  }
  return 0.0;
}

LobeErrors lobe_errors(LobeModel model, const LobeGrid& grid, const LobeData& data,
                       const LobeObservations& observations, const LobeParameters& parameters) {
  double difference = 0.0, total = 0.0, plane_difference = 0.0, plane_total = 0.0, noise = 0.0;
  for (const std::size_t bin : observations.bins) {
    const double measured = data.mean[bin];
    const double model_value = std::exp(log_bin_average(model, grid, bin, parameters));
    const double omega = grid.solid_angle(bin);
    difference += omega * std::abs(model_value - measured);
    total += omega * measured;
    noise += omega * data.stderr_of_mean[bin];
    if (grid.in_symmetry_plane(bin)) {
      plane_difference += omega * std::abs(model_value - measured);
      plane_total += omega * measured;
    }
  }
  LobeErrors errors;
  if (total > 0.0 && std::isfinite(difference)) {
    errors.sphere = difference / total;
    errors.noise = std::sqrt(2.0 / pi) * noise / total;
  }
  if (plane_total > 0.0 && std::isfinite(plane_difference)) {
    errors.plane = plane_difference / plane_total;
  }
  return errors;
}

}  // namespace scatterlab::fit
