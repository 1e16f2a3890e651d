// Cost of the lobe fits: fits/s of each model on one lobe of the paper's 18 x 36 grid, by
// quadrature order (nodes per bin = order^2), and of scatterlab fit's whole 15 x 40 grid of such
// lobes with all models on 1 and 2 threads.
//
//   ./build/bench/scatterlab_bench --benchmark_filter=Fit --benchmark_counters_tabular=true
//
// The lobe is an anisotropic double exponential (flattened across the phi = 0 plane, as near
// the beam) with 5 % noise, so that every model has work to do.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

#include "scatterlab/core/random.hpp"
#include "scatterlab/fit/lobe_fits_file.hpp"

namespace scatterlab {
namespace {

using fit::LobeModel;

std::vector<double> edges(double max, int bins) {
  std::vector<double> values;
  for (int i = 0; i <= bins; ++i) values.push_back(max * i / bins);
  return values;
}

fit::LobeGrid papers_grid(int order) {
  return fit::LobeGrid(edges(std::numbers::pi, 18), edges(2.0 * std::numbers::pi, 36), false,
                       order);
}

// Bin averages of a flattened lobe times (1 + 0.05 u), u uniform in (-sqrt 3, sqrt 3).
void synthetic_lobe(const fit::LobeGrid& grid, std::uint64_t seed, std::vector<double>& mean,
                    std::vector<double>& error) {
  fit::LobeParameters truth;
  truth.axis = Eigen::Vector3d(std::sin(0.6), 0.0, std::cos(0.6));
  truth.shape = fit::double_exponential_shape(-3.0, 8.0, -3.0, -1.5);
  for (std::size_t bin = 0; bin < grid.size(); ++bin) {
    const double value = std::exp(fit::log_bin_average(LobeModel::adexp, grid, bin, truth));
    PhotonRandom random(seed, bin);
    mean.push_back(value * (1.0 + 0.05 * std::sqrt(3.0) * (2.0 * random.next() - 1.0)));
    error.push_back(0.05 * value);
  }
}

void FitOneLobe(benchmark::State& state) {
  const auto model = static_cast<LobeModel>(state.range(0));
  const fit::LobeGrid grid = papers_grid(static_cast<int>(state.range(1)));
  std::vector<double> mean, error;
  synthetic_lobe(grid, 1, mean, error);
  const fit::LobeData data{mean, error, Eigen::Vector3d(std::sin(0.6), 0.0, std::cos(0.6))};
  const fit::LobeObservations o = fit::observe(grid, data, {});
  fit::LobeParameters start = model == LobeModel::sg || model == LobeModel::sg_free
                                  ? fit::spherical_gaussian_estimate(grid, o, data.flux)
                                  : fit::double_exponential_estimate(grid, o);
  if (model == LobeModel::asg) start = fit::asg_from_sg(start);
  if (model == LobeModel::adexp_ridge || model == LobeModel::adexp2_ridge) {
    start = fit::ridge_from_adexp(grid, o, start, true);
  }
  if (model == LobeModel::adexp2_ridge) start = fit::second_lobe_starts(start).back();
  std::int64_t iterations = 0;
  for (auto _ : state) {
    const fit::LobeFit result = fit::fit_lobe(model, grid, data, o, start);
    benchmark::DoNotOptimize(result.cost);
    iterations += result.iterations;
  }
  state.SetLabel(fit::to_string(model));
  state.counters["fits/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["ceres_iterations"] =
      static_cast<double>(iterations) / static_cast<double>(state.iterations());
}
BENCHMARK(FitOneLobe)
    ->ArgsProduct({{0, 1, 2, 3, 4, 5, 6, 7}, {3}})
    ->ArgsProduct({{4}, {1, 2, 5}})
    ->Unit(benchmark::kMillisecond);

// The whole default grid of 15 x 40 spatial bins, each a different noisy copy of the lobe.
void FitWholeGrid(benchmark::State& state) {
  const fit::LobeGrid grid = papers_grid(3);
  fit::RadianceLobes lobes;
  lobes.r_edges = edges(1.5, 15);
  lobes.z_edges = edges(4.0, 40);
  lobes.theta_edges = edges(std::numbers::pi, 18);
  lobes.phi_edges = edges(2.0 * std::numbers::pi, 36);
  for (std::uint64_t bin = 0; bin < 600; ++bin) {
    synthetic_lobe(grid, bin, lobes.mean, lobes.stderr_of_mean);
    lobes.flux.insert(lobes.flux.end(), {std::sin(0.6), 0.0, std::cos(0.6)});
  }
  const std::vector<LobeModel> models(fit::kAllLobeModels.begin(), fit::kAllLobeModels.end());
  std::size_t fits = 0;
  for (auto _ : state) {
    fits +=
        fit::fit_lobes(lobes, grid, models, {}, static_cast<int>(state.range(0))).attempted_fits;
  }
  state.counters["fits/s"] =
      benchmark::Counter(static_cast<double>(fits), benchmark::Counter::kIsRate);
}
BENCHMARK(FitWholeGrid)->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace
}  // namespace scatterlab
