// Collision against track-length estimator on the point-source scene (isotropic point source,
// g = 0.9, albedo 0.5): the whole run's time and the figure of merit 1/(R^2 T)
// (tally/figure_of_merit.hpp) of the tallies the summary reports, so that the estimator's cost
// per photon is weighed against the error it buys.
//
//   ./build/bench/scatterlab_bench --benchmark_filter=FigureOfMerit
//   --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <string>

#include "scatterlab/tally/figure_of_merit.hpp"
#include "scatterlab/transport/simulate.hpp"

namespace scatterlab {
namespace {

void FigureOfMerit(benchmark::State& state, Estimator estimator) {
  InfiniteMediumSpec spec;
  spec.set_source(SourceKind::point);
  spec.tallies.radiance = false;
  spec.tallies.fluence_spherical = true;
  spec.tallies.estimator = estimator;
  spec.run.photons = 1'000'000;
  spec.run.batches = 16;
  spec.run.threads = 1;
  TransportOutput out;
  for (auto _ : state) out = run_infinite_medium(spec);
  for (const char* name : {"absorbed", "fluence", "fluence_spherical"}) {
    const TallyResult* tally = find_tally(out.tallies, name);
    if (tally == nullptr) continue;
    state.counters[std::string("FOM ") + name] = figure_of_merit(
        relative_standard_error(tally->mean, tally->stderr_of_mean), out.wall_seconds);
  }
  state.counters["photons/s"] = static_cast<double>(out.photons) / out.wall_seconds;
}

BENCHMARK_CAPTURE(FigureOfMerit, collision, Estimator::collision)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(FigureOfMerit, track_length, Estimator::track_length)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace scatterlab
