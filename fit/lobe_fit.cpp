#include "scatterlab/fit/lobe_fit.hpp"

#include <ceres/ceres.h>
#include <fmt/format.h>
#include <glog/logging.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>
#include <utility>

#include "double_exponential_cost.hpp"
#include "scatterlab/core/constants.hpp"

namespace scatterlab::fit {

namespace {

// Without any standard error (noise-free data): sigma = 1e-6 of L, at least 1e-12 of the
// brightest L (lobe_fit.hpp).
constexpr double kNoiseFreeRelative = 1e-6, kNoiseFreeFloor = 1e-12;
// The ridge's start: an HG-like forward peak, a mild attenuation and a sharp onset (ridge.hpp);
// its amplitude and onset come from the data (ridge_from_adexp).
constexpr double kRidgeStartG = 0.8, kRidgeStartK = 0.5, kRidgeStartWidth = 0.05;
constexpr double kRidgeStartKappa = 10.0;  // a spread of ~1/sqrt(10) rad, 18 degrees
// The second lobe's starts (second_lobe_starts): e^{-30} of the first (a change of the chi-square
// below 1e-12 of it), or tilted 0.3 rad towards e_r.
constexpr double kFaintSecondLobe = 30.0, kSecondLobeTilt = 0.3;

inline bool finite(double x) {
  return std::isfinite(x);
}
// ceres::isfinite looks at a Jet's value only; Ceres checks the derivatives too.
template <typename T, int N>
bool finite(const ceres::Jet<T, N>& x) {
  return std::isfinite(x.a) && x.v.allFinite();
}

// log of the model averaged over one angular bin: log sum_q w_q exp(l_q), kept relative to the
// largest l_q seen so far (rescaling the sum when a larger one comes), so that a lobe with
// lambda ~ 1e3 neither overflows nor underflows, in one pass and without a buffer of Jets.
template <class Evaluator, typename T = decltype(std::declval<Evaluator>().log_value({}))>
T log_average(const LobeGrid& grid, std::size_t bin, const Evaluator& lobe) {
  using std::exp;
  using std::log;
  const std::span<const LobeNode> nodes = grid.nodes(bin);
  T largest = lobe.log_value(nodes[0].direction);
  T sum(nodes[0].weight);
  for (std::size_t q = 1; q < nodes.size(); ++q) {
    const T value = lobe.log_value(nodes[q].direction);
    if (value > largest) {
      sum = sum * exp(largest - value) + nodes[q].weight;
      largest = value;
    } else {
      sum += nodes[q].weight * exp(value - largest);
    }
  }
  return largest + log(sum);
}

// The model averaged over bin i: its smooth part by the bin's nodes, and for adexp_ridge the
// ridge by the bin's ridge nodes.
template <class Evaluator, typename T = decltype(std::declval<Evaluator>().log_value({}))>
T bin_value(const LobeGrid& grid, std::size_t bin, const Evaluator& lobe) {
  using std::exp;
  T value = exp(log_average(grid, bin, lobe));
  if constexpr (requires { lobe.ridge_density(0.0); }) {
    for (const RidgeNode& node : grid.ridge_nodes(bin)) {
      value += node.weight * lobe.ridge_density(node.theta);
    }
    value += lobe.spread_average(bin / grid.phi_bins(), bin % grid.phi_bins());
  }
  return value;
}

// The chi-square residuals of lobe_fit.hpp, (<m>_i - L_i) / sigma_i. false (Ceres rejects the
// step quietly) where a value or derivative is not finite: a trial step far out on a lobe can
// overflow e^{log <m>}, and Ceres warns about every non-finite residual it is handed.
template <typename T, class Evaluator>
bool chi_residuals(const LobeGrid& grid, const LobeObservations& o, const Evaluator& lobe,
                   T* residuals) {
  for (std::size_t i = 0; i < o.radiance.size(); ++i) {
    residuals[i] = (bin_value(grid, i, lobe) - o.radiance[i]) / o.sigma[i];
    if (!finite(residuals[i])) return false;
  }
  return true;
}

template <class Model>
struct LobeResidual {
  const LobeGrid* grid;
  const LobeObservations* observations;

  template <typename T>
  bool operator()(const T* axis, const T* shape, T* residuals) const {
    return chi_residuals(*grid, *observations, typename Model::template Evaluator<T>(axis, shape),
                         residuals);
  }
};

template <class Evaluator>
double cost_with(const LobeGrid& grid, const LobeObservations& o, const Evaluator& lobe) {
  double cost = 0.0;
  for (std::size_t i = 0; i < o.radiance.size(); ++i) {
    const double r = (bin_value(grid, i, lobe) - o.radiance[i]) / o.sigma[i];
    cost += 0.5 * r * r;
  }
  return std::isfinite(cost) ? cost : std::numeric_limits<double>::infinity();
}

// Calls f with the double Evaluator of `model` at `p`.
template <class F>
auto with_evaluator(LobeModel model, const LobeGrid& grid, const LobeParameters& p, F&& f) {
  const double* axis = p.axis.data();
  const double* shape = p.shape.data();
  switch (model) {
    case LobeModel::sg:
    case LobeModel::sg_free:
      return f(SphericalGaussian::Evaluator<double>(axis, shape));
    case LobeModel::dexp_paper:
    case LobeModel::dexp:
      return f(DoubleExponential::Evaluator<double>(axis, shape));
    case LobeModel::adexp:
      return f(AnisotropicDoubleExponential::Evaluator<double>(axis, shape));
    case LobeModel::asg:
      return f(AnisotropicSphericalGaussian::Evaluator<double>(axis, shape));
    case LobeModel::adexp_ridge:
      return f(AnisotropicRidge::Evaluator<double>(axis, shape, p.ridge.data(), grid));
    case LobeModel::adexp2_ridge:
      break;
  }
  return f(TwoLobeRidge::Evaluator<double>(axis, shape, p.ridge.data(), grid, p.second_axis.data(),
                                           p.second_shape.data()));
}

// A bound on one parameter: block 0 = shape, 1 = ridge, 2 = the second lobe's shape. `artificial`:
// a fit that ends on it is at_bound (lambda >= 0, c >= 0, k >= 0 and theta_on in [0, pi] are the
// models' own domains; a ridge onset narrower than 1e-3 rad, or wider than 1 rad, cannot be told
// apart from one at those widths on bins of a few degrees).
struct Bound {
  int block;
  int index;
  double lower, upper;
  bool artificial_lower, artificial_upper;
};

std::vector<Bound> bounds(LobeModel model) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  const Bound gamma{0, 2, -kGammaBound, kGammaBound, true, true};
  const Bound eta{0, 3, -kEtaBound, kEtaBound, true, true};
  switch (model) {
    case LobeModel::sg:
    case LobeModel::sg_free:
      return {{0, 0, 0.0, kSharpnessBound, false, true}};
    case LobeModel::dexp_paper:
    case LobeModel::dexp:
      return {gamma};
    case LobeModel::adexp:
      return {gamma, eta};
    case LobeModel::asg:
      return {{0, 1, 0.0, kSharpnessBound, false, true}, {0, 2, 0.0, kSharpnessBound, false, true}};
    case LobeModel::adexp2_ridge: {
      std::vector<Bound> all = bounds(LobeModel::adexp_ridge);
      all.push_back({2, 2, -kGammaBound, kGammaBound, true, true});
      all.push_back({2, 3, -kEtaBound, kEtaBound, true, true});
      return all;
    }
    case LobeModel::adexp_ridge:
      return {gamma,
              eta,
              {1, 0, 0.0, inf, false, false},
              {1, 1, -kRidgeGBound, kRidgeGBound, true, true},
              {1, 2, 0.0, kSharpnessBound, false, true},
              {1, 3, 0.0, pi, false, false},
              {1, 4, 1e-3, 1.0, false, false},
              {1, 5, 0.0, inf, false, false},
              {1, 6, 0.0, kSharpnessBound, false, true}};
  }
  return {};
}

double& parameter(LobeParameters& p, const Bound& b) {
  const auto index = static_cast<std::size_t>(b.index);
  return b.block == 0 ? p.shape[index] : b.block == 1 ? p.ridge[index] : p.second_shape[index];
}

// Keeps a starting point inside the bounds (Ceres refuses infeasible ones).
LobeParameters feasible(LobeModel model, LobeParameters start) {
  start.axis.normalize();
  start.second_axis.normalize();
  for (const Bound& b : bounds(model)) {
    double& value = parameter(start, b);
    value = std::clamp(value, b.lower, b.upper);
  }
  return start;
}

// The ridge's shape (g, k, theta_on, width) means nothing once its amplitude c is 0, nor the
// spread's kappa once c_spread is 0: such a parameter on its bound says nothing of the fit.
bool without_effect(const LobeParameters& p, const Bound& b) {
  return b.block == 1 && ((b.index >= 1 && b.index <= 4 && p.ridge[0] == 0.0) ||
                          (b.index == 6 && p.ridge[5] == 0.0));
}

bool on_artificial_bound(LobeModel model, LobeParameters p) {
  for (const Bound& b : bounds(model)) {
    if (without_effect(p, b)) continue;
    const double value = parameter(p, b);
    const auto near = [value](double bound) {
      return std::abs(value - bound) <= 1e-6 * std::max(1.0, std::abs(bound));
    };
    if ((b.artificial_lower && near(b.lower)) || (b.artificial_upper && near(b.upper))) return true;
  }
  return false;
}

void set_bounds(LobeModel model, ceres::Problem& problem, double* shape, double* ridge,
                double* second_shape) {
  for (const Bound& b : bounds(model)) {
    double* block = b.block == 0 ? shape : b.block == 1 ? ridge : second_shape;
    if (std::isfinite(b.lower)) problem.SetParameterLowerBound(block, b.index, b.lower);
    if (std::isfinite(b.upper)) problem.SetParameterUpperBound(block, b.index, b.upper);
  }
}

// Ceres logs through glog, to stderr, things a fit's status already says or that do not change
// its outcome (e.g. "Failed to extract eigenvalues from companion matrix" where the bounded line
// search falls back to bisection), and they would be the only lines of a fit without a bin's
// name. Only fatal ones still print; call_once orders the write before every thread's solve.
void quiet_solver_log() {
  static std::once_flag once;
  std::call_once(once, [] { FLAGS_minloglevel = google::GLOG_FATAL; });
}

LobeFit solve(LobeModel model, const LobeGrid& grid, const LobeObservations& o,
              const LobeParameters& start, const FitOptions& options) {
  quiet_solver_log();
  LobeFit fit;
  fit.parameters = feasible(model, start);
  LobeParameters& p = fit.parameters;
  double* axis = p.axis.data();
  double* shape = p.shape.data();
  double* ridge = p.ridge.data();
  double* second_axis = p.second_axis.data();
  double* second_shape = p.second_shape.data();
  const int residuals = static_cast<int>(o.radiance.size());

  ceres::Problem problem;
  switch (model) {
    case LobeModel::sg:
    case LobeModel::sg_free:
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<LobeResidual<SphericalGaussian>, ceres::DYNAMIC, 3, 2>(
              new LobeResidual<SphericalGaussian>{&grid, &o}, residuals),
          nullptr, axis, shape);
      break;
    case LobeModel::dexp_paper:
    case LobeModel::dexp:
    case LobeModel::adexp:
      problem.AddResidualBlock(new DoubleExponentialCost(grid, o, model), nullptr, axis, shape);
      break;
    case LobeModel::asg:
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<LobeResidual<AnisotropicSphericalGaussian>,
                                          ceres::DYNAMIC, 3, 3>(
              new LobeResidual<AnisotropicSphericalGaussian>{&grid, &o}, residuals),
          nullptr, axis, shape);
      break;
    case LobeModel::adexp_ridge:
      problem.AddResidualBlock(new DoubleExponentialCost(grid, o, model), nullptr, axis, shape,
                               ridge);
      break;
    case LobeModel::adexp2_ridge:
      problem.AddResidualBlock(new DoubleExponentialCost(grid, o, model), nullptr, axis, shape,
                               ridge, second_axis, second_shape);
      problem.SetManifold(second_axis, new ceres::SphereManifold<3>());
      break;
  }
  if (model == LobeModel::sg) {
    problem.SetParameterBlockConstant(axis);  // p = E / |E| (Vavassori §4.2.1)
  } else {
    problem.SetManifold(axis, new ceres::SphereManifold<3>());
  }
  set_bounds(model, problem, shape, ridge, second_shape);

  // Ceres logs an error when it cannot evaluate the starting point; say it here instead.
  double start_cost = 0.0;
  std::vector<double> start_gradient;
  if (!problem.Evaluate(ceres::Problem::EvaluateOptions(), &start_cost, nullptr, &start_gradient,
                        nullptr)) {
    fit.status = FitStatus::non_finite;
    fit.message = "the model or its derivatives are not finite at the starting point";
    return fit;
  }

  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options.max_iterations;
  // chi^2 is at least about the number of directions (~600): a relative change of 1e-6 in it
  // is ~1e-3, far below the change of 1 that is statistically significant. (1e-5 stops the
  // slow fits of the ridge early: on the 1e8-photon beam its 90th percentile of error / noise
  // rose from 4.5 to 6.9 for a third less time.)
  solver.function_tolerance = 1e-6;
  solver.parameter_tolerance = 1e-7;
  // With bounds, Ceres follows every step with a projected Armijo line search, whose default
  // cubic interpolation evaluates the gradient, a whole Jacobian, at each trial point. For the
  // double exponentials, whose Jacobian is most of a fit's time, bisection on the cost alone:
  // on the 1e8-photon beam of the README it takes adexp2_ridge from 95 % to 99.7 % of bins within
  // 2x the noise and all the fits from 26.5 to 20 s; the SG family (Jets, cheap) keeps the cubic
  // steps, which reached a lower chi-square in 24 of 595 asg bins.
  if (DoubleExponentialCost::serves(model)) {
    solver.line_search_interpolation_type = ceres::BISECTION;
  }
  solver.logging_type = ceres::SILENT;
  solver.num_threads = 1;  // bins run in parallel instead
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);

  p.axis.normalize();
  p.second_axis.normalize();
  // The cost at the parameters returned, not Ceres's final_cost, which can differ from it in the
  // sixth digit (measured: 54.5576 against 54.5580): the superset checks compare these.
  if (!problem.Evaluate(ceres::Problem::EvaluateOptions(), &fit.cost, nullptr, nullptr, nullptr)) {
    fit.cost = std::numeric_limits<double>::infinity();
  }
  fit.iterations = static_cast<int>(summary.iterations.size());
  bool is_finite = std::isfinite(fit.cost) && p.axis.allFinite();
  for (const double value : p.shape) is_finite = is_finite && std::isfinite(value);
  for (const double value : p.ridge) is_finite = is_finite && std::isfinite(value);
  for (const double value : p.second_shape) is_finite = is_finite && std::isfinite(value);
  is_finite = is_finite && p.second_axis.allFinite();
  if (!is_finite) {
    fit.status = FitStatus::non_finite;
    fit.message = "non-finite parameters or cost after the solve";
  } else if (summary.termination_type == ceres::CONVERGENCE) {
    fit.status = on_artificial_bound(model, p) ? FitStatus::at_bound : FitStatus::converged;
    if (fit.status == FitStatus::at_bound) fit.message = "a parameter ended on its bound";
  } else if (summary.termination_type == ceres::NO_CONVERGENCE) {
    fit.status = FitStatus::iteration_limit;
    fit.message = summary.message;
  } else {
    fit.status = FitStatus::solver_failure;
    fit.message = summary.message;
  }
  return fit;
}

double log_weight(const LobeObservations& o, std::size_t i) {
  const double w = o.radiance[i] / o.sigma[i];
  return w * w;
}

// Solid-angle-weighted mean of log L over the directions with L > 0 and
// |p.c - target| <= half_width.
double ring_mean(const LobeGrid& grid, const LobeObservations& o, const Eigen::Vector3d& axis,
                 double target, double half_width) {
  double sum = 0.0, weight = 0.0;
  for (std::size_t i = 0; i < o.radiance.size(); ++i) {
    if (o.radiance[i] > 0.0 && std::abs(axis.dot(grid.centre(i)) - target) <= half_width) {
      sum += grid.solid_angle(i) * std::log(o.radiance[i]);
      weight += grid.solid_angle(i);
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

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

std::string to_string(FitStatus status) {
  switch (status) {
    case FitStatus::converged:
      return "converged";
    case FitStatus::iteration_limit:
      return "iteration_limit";
    case FitStatus::solver_failure:
      return "solver_failure";
    case FitStatus::non_finite:
      return "non_finite";
    case FitStatus::at_bound:
      return "at_bound";
    case FitStatus::estimate:
      return "estimate";
    case FitStatus::all_zero:
      return "all_zero";
    case FitStatus::too_few_directions:
      return "too_few_directions";
    case FitStatus::non_finite_input:
      return "non_finite_input";
    case FitStatus::no_axis:
      return "no_axis";
  }
  return "unknown";
}

std::string fit_status_legend() {
  std::string legend;
  for (const FitStatus status :
       {FitStatus::converged, FitStatus::iteration_limit, FitStatus::solver_failure,
        FitStatus::non_finite, FitStatus::at_bound, FitStatus::estimate, FitStatus::all_zero,
        FitStatus::too_few_directions, FitStatus::non_finite_input, FitStatus::no_axis}) {
    legend += fmt::format("{}{} {}", legend.empty() ? "" : "; ", static_cast<int>(status),
                          to_string(status));
  }
  return legend +
         " (0 Ceres converged inside the bounds; 1 iteration limit; 4 converged onto an "
         "artificial bound; 5 the paper's estimate, not solved: 0, 1, 4, 5 are fitted. 2, 3 and "
         "10 and above: parameters 0, errors -1)";
}

LobeObservations observe(const LobeGrid& grid, const LobeData& data, const FitOptions& options) {
  LobeObservations o;
  bool any_radiance = false;
  for (std::size_t bin = 0; bin < grid.size(); ++bin) {
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
  // Q = median of stderr^2 Omega / L: one event's radiance times its solid angle (header).
  std::vector<double> events;
  double brightest = 0.0;
  for (std::size_t bin = 0; bin < grid.size(); ++bin) {
    const double mean = data.mean[bin], error = data.stderr_of_mean[bin];
    brightest = std::max(brightest, std::abs(mean));
    if (mean > 0.0 && error > 0.0) events.push_back(error * error * grid.solid_angle(bin) / mean);
    if (mean > 0.0 && error <= options.max_relative_stderr * mean) ++o.resolved;
  }
  o.event_radiance = median(events);
  for (std::size_t bin = 0; bin < grid.size(); ++bin) {
    const double error = data.stderr_of_mean[bin];
    const double floor =
        o.event_radiance > 0.0
            ? o.event_radiance / grid.solid_angle(bin)
            : std::max(kNoiseFreeRelative * std::abs(data.mean[bin]), kNoiseFreeFloor * brightest);
    o.radiance.push_back(data.mean[bin]);
    o.stderr_of_mean.push_back(error);
    o.sigma.push_back(std::max(error, floor));
  }
  if (o.resolved < options.min_directions) {
    o.status = FitStatus::too_few_directions;
    o.message =
        fmt::format("only {} of {} directions have radiance with relative stderr <= {}; {} needed",
                    o.resolved, grid.size(), options.max_relative_stderr, options.min_directions);
  }
  return o;
}

double fit_cost(LobeModel model, const LobeGrid& grid, const LobeObservations& observations,
                const LobeParameters& parameters) {
  const LobeParameters p = feasible(model, parameters);
  return with_evaluator(model, grid, p,
                        [&](const auto& lobe) { return cost_with(grid, observations, lobe); });
}

LobeFit fit_lobe(LobeModel model, const LobeGrid& grid, const LobeData& /*data*/,
                 const LobeObservations& observations, const LobeParameters& start,
                 const FitOptions& options) {
  LobeFit fit;
  if (model == LobeModel::dexp_paper) {
    fit.parameters = feasible(model, start);
    fit.cost = fit_cost(model, grid, observations, fit.parameters);
    fit.status = std::isfinite(fit.cost) ? FitStatus::estimate : FitStatus::non_finite;
  } else {
    fit = solve(model, grid, observations, start, options);
  }
  if (usable(fit.status)) {
    const LobeErrors errors = lobe_errors(model, grid, observations, fit.parameters);
    fit.error_sphere = errors.sphere;
    fit.error_plane = errors.plane;
    fit.noise = errors.noise;
    fit.chi2_dof = errors.chi2_dof;
  }
  return fit;
}

namespace {

// The SG `p` with mu scaled to its chi-square optimum: the model is linear in mu, so
// mu* = sum L m / sigma^2 / sum m^2 / sigma^2 over the bin averages m of mu = 1.
LobeParameters with_best_amplitude(const LobeGrid& grid, const LobeObservations& o,
                                   LobeParameters p) {
  p.shape[1] = 0.0;
  double sxy = 0.0, sxx = 0.0;
  const SphericalGaussian::Evaluator<double> lobe(p.axis.data(), p.shape.data());
  for (std::size_t i = 0; i < o.radiance.size(); ++i) {
    const double m = std::exp(log_average(grid, i, lobe)), w = 1.0 / (o.sigma[i] * o.sigma[i]);
    sxy += w * m * o.radiance[i];
    sxx += w * m * m;
  }
  if (sxx > 0.0 && sxy > 0.0 && std::isfinite(sxx) && std::isfinite(sxy)) {
    p.shape[1] = std::log(sxy) - std::log(sxx);
  }
  return p;
}

}  // namespace

LobeParameters spherical_gaussian_estimate(const LobeGrid& grid, const LobeObservations& o,
                                           const Eigen::Vector3d& axis) {
  // log L = log mu + lambda x with x = p.c - 1 (§4.2.1), weighted least squares.
  double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < o.radiance.size(); ++i) {
    if (!(o.radiance[i] > 0.0)) continue;
    const double w = log_weight(o, i);
    const double x = axis.dot(grid.centre(i)) - 1.0, y = std::log(o.radiance[i]);
    sw += w, sx += w * x, sy += w * y, sxx += w * x * x, sxy += w * x * y;
  }
  LobeParameters start;
  start.axis = axis.normalized();
  const double determinant = sw * sxx - sx * sx;
  double lambda = determinant > 0.0 ? (sw * sxy - sx * sy) / determinant : 0.0;
  if (!(lambda > 0.0)) lambda = 0.0;
  start.shape[0] = std::min(lambda, kSharpnessBound);
  start.shape[1] = sw > 0.0 ? (sy - lambda * sx) / sw : 0.0;
  // Bin centres say nothing of a lobe narrower than a bin (lambda ~ 1e3 on 10-degree bins),
  // and from a start far off in sharpness a fit in L sees no gradient. So lambda is also tried
  // on a grid of 4 per decade from 1e-3 to 1e5, each with its best amplitude, and the lowest
  // chi-square kept.
  double best = fit_cost(LobeModel::sg, grid, o, with_best_amplitude(grid, o, start));
  LobeParameters trial = start;
  for (int k = -12; k <= 20; ++k) {
    trial.shape[0] = std::pow(10.0, 0.25 * k);
    trial = with_best_amplitude(grid, o, trial);
    const double cost = fit_cost(LobeModel::sg, grid, o, trial);
    if (cost < best) best = cost, start = trial;
  }
  return start;
}

LobeParameters double_exponential_estimate(const LobeGrid& grid, const LobeObservations& o) {
  // Step 1: p and M = L(p) from the brightest direction.
  std::size_t peak = 0;
  for (std::size_t i = 1; i < o.radiance.size(); ++i) {
    if (o.radiance[i] > o.radiance[peak]) peak = i;
  }
  LobeParameters start;
  start.axis = grid.centre(peak);
  const double log_peak = std::log(o.radiance[peak]);

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
  for (std::size_t i = 0; i < o.radiance.size(); ++i) {
    if (!(o.radiance[i] > 0.0)) continue;
    const double s = std::sqrt(std::max(0.0, 1.0 - start.axis.dot(grid.centre(i))));
    const double e = std::exp(gamma * s), w = log_weight(o, i);
    const double x = 1.0 - e, y = std::log(o.radiance[i]) - log_peak * e;
    sxy += w * x * y;
    sxx += w * x * x;
  }
  const double log_alpha = sxx > 0.0 ? sxy / sxx : log_peak - 1.0;
  // Step 4: beta = log M - log alpha.
  start.shape = double_exponential_shape(log_alpha, log_peak - log_alpha, gamma);
  return start;
}

LobeParameters asg_from_sg(const LobeParameters& sg) {
  LobeParameters asg;
  asg.axis = sg.axis;
  const double half = std::min(0.5 * sg.shape[0], kSharpnessBound);
  asg.shape = {sg.shape[1], half, half, 0.0};
  return asg;
}

std::vector<LobeParameters> second_lobe_starts(const LobeParameters& ridge) {
  LobeParameters tilted = ridge;
  tilted.second_axis = (ridge.axis + Eigen::Vector3d(kSecondLobeTilt, 0.0, 0.0)).normalized();
  tilted.second_shape = {ridge.shape[0] - std::log(2.0), 0.5 * ridge.shape[1], ridge.shape[2], 0.0};
  // Not a copy of the first lobe: two identical lobes give the solver two equal columns.
  LobeParameters faint = tilted;
  faint.second_shape[0] = ridge.shape[0] - kFaintSecondLobe;
  return {faint, tilted};
}

LobeParameters ridge_from_adexp(const LobeGrid& grid, const LobeObservations& o,
                                const LobeParameters& adexp, bool with_ridge) {
  LobeParameters start = adexp;
  start.ridge = {0.0, kRidgeStartG, kRidgeStartK, 0.0, kRidgeStartWidth, 0.0, kRidgeStartKappa};
  if (!with_ridge) return start;
  // The onset where the tally on the line lies most standard errors above the smooth lobe.
  const AnisotropicDoubleExponential::Evaluator<double> lobe(adexp.axis.data(), adexp.shape.data());
  std::vector<double> excess(o.radiance.size(), 0.0);
  std::size_t worst = o.radiance.size();
  double worst_z = 0.0;
  for (std::size_t i = 0; i < o.radiance.size(); ++i) {
    if (grid.ridge_nodes(i).empty()) continue;
    excess[i] = o.radiance[i] - std::exp(log_average(grid, i, lobe));
    if (excess[i] / o.sigma[i] > worst_z) worst = i, worst_z = excess[i] / o.sigma[i];
  }
  if (worst == o.radiance.size()) return start;
  start.ridge[3] = grid.ridge_nodes(worst).front().theta - 0.05;
  start.ridge[3] = std::clamp(start.ridge[3], 0.0, pi);
  // c by weighted least squares of the excess on the profile (linear in c).
  start.ridge[0] = 1.0;
  const AnisotropicRidge::Evaluator<double> unit(adexp.axis.data(), adexp.shape.data(),
                                                 start.ridge.data(), grid);
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t i = 0; i < o.radiance.size(); ++i) {
    double profile = 0.0;
    for (const RidgeNode& node : grid.ridge_nodes(i))
      profile += node.weight * unit.ridge_density(node.theta);
    const double w = 1.0 / (o.sigma[i] * o.sigma[i]);
    sxy += w * profile * excess[i];
    sxx += w * profile * profile;
  }
  start.ridge[0] = sxx > 0.0 && sxy > 0.0 ? sxy / sxx : 0.0;
  return start;
}

double log_bin_average(LobeModel model, const LobeGrid& grid, std::size_t bin,
                       const LobeParameters& p) {
  return with_evaluator(model, grid, p,
                        [&](const auto& lobe) { return std::log(bin_value(grid, bin, lobe)); });
}

LobeErrors lobe_errors(LobeModel model, const LobeGrid& grid, const LobeObservations& o,
                       const LobeParameters& parameters) {
  double difference = 0.0, total = 0.0, plane_difference = 0.0, plane_total = 0.0, noise = 0.0,
         chi2 = 0.0;
  with_evaluator(model, grid, parameters, [&](const auto& lobe) {
    for (std::size_t bin = 0; bin < o.radiance.size(); ++bin) {
      const double measured = o.radiance[bin];
      const double model_value = bin_value(grid, bin, lobe);
      const double omega = grid.solid_angle(bin);
      const double r = (model_value - measured) / o.sigma[bin];
      chi2 += r * r;
      difference += omega * std::abs(model_value - measured);
      total += omega * measured;
      noise += omega * o.stderr_of_mean[bin];
      if (grid.in_symmetry_plane(bin)) {
        plane_difference += omega * std::abs(model_value - measured);
        plane_total += omega * measured;
      }
    }
    return 0;
  });
  LobeErrors errors;
  if (total > 0.0 && std::isfinite(difference)) {
    errors.sphere = difference / total;
    errors.noise = std::sqrt(2.0 / pi) * noise / total;
  }
  if (plane_total > 0.0 && std::isfinite(plane_difference)) {
    errors.plane = plane_difference / plane_total;
  }
  const double dof = static_cast<double>(o.radiance.size()) - free_parameters(model);
  if (dof > 0.0 && std::isfinite(chi2)) errors.chi2_dof = chi2 / dof;
  return errors;
}

}  // namespace scatterlab::fit
