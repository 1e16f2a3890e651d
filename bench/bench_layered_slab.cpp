// Cost of the layered slab's random walk (transport/slab.hpp) on MCML's own inputs: its sample
// (data/mcml/sample.mci, three layers of n 1.37) and a three-layer skin model
// (data/mcml/skin.mci), with every MCML tally on, analog and with MCML's implicit capture.
// SlabWalk times the walk on one thread (photons/s, ns per scattering event: the figures to hold
// against MCML 1.2.2's, which scores the same way with implicit capture); SlabRun runs the whole
// engine (batches, threads, reduction) on 1 and 2 threads for the speed-up.
//
//   ./build/bench/scatterlab_bench --benchmark_filter='Slab' --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>
#include <vector>

#include "scatterlab/core/phase_function.hpp"
#include "scatterlab/io/mcml_input.hpp"
#include "scatterlab/tally/scorer.hpp"
#include "scatterlab/tally/tally_book.hpp"
#include "scatterlab/transport/lane_walk.hpp"
#include "scatterlab/transport/layered_slab.hpp"
#include "scatterlab/transport/random_walk.hpp"
#include "scatterlab/transport/slab.hpp"
#include "walk_timing.hpp"

namespace scatterlab {
namespace {

LayeredSlabSpec mcml_spec(const std::string& name, Weighting weighting) {
  const auto path = std::filesystem::path(SCATTERLAB_SOURCE_DIR) / "data/mcml" / name;
  LayeredSlabSpec spec = layered_slab_spec(read_mcml_input(path).at(0));
  spec.weighting = weighting;
  return spec;
}

template <Weighting weighting>
void time_slab_walk(benchmark::State& state, const std::string& name) {
  const TransportProblem problem = transport_problem(mcml_spec(name, weighting));
  const TallyBook book(problem.tallies, problem.split_by_order);
  const Scorer scorer(problem.axes, book);
  const RandomWalk<Slab, IsotropicPhase, Estimator::none, weighting> walk(
      Slab(problem.layers, problem.n_above, problem.n_below), IsotropicPhase{}, problem.source,
      scorer, problem.albedo, problem.run.escape_radius, problem.run.seed);
  bench::time_walk(state, walk, book.size());
}

void SlabWalk(benchmark::State& state, const std::string& name, Weighting weighting) {
  if (weighting == Weighting::implicit_capture) {
    return time_slab_walk<Weighting::implicit_capture>(state, name);
  }
  time_slab_walk<Weighting::analog>(state, name);
}

void SlabLanes(benchmark::State& state, const std::string& name, Weighting weighting) {
  const TransportProblem problem = transport_problem(mcml_spec(name, weighting));
  const TallyBook book(problem.tallies, problem.split_by_order);
  const Scorer scorer(problem.axes, book);
  const LaneWalk walk(Slab(problem.layers, problem.n_above, problem.n_below), weighting, scorer,
                      problem.source, problem.run.escape_radius, problem.run.seed);
  bench::time_walk(state, walk, book.size());
  state.counters["lanes"] = LaneWalk::lanes();
}

void SlabRun(benchmark::State& state, const std::string& name, Weighting weighting) {
  LayeredSlabSpec spec = mcml_spec(name, weighting);
  spec.run.photons = 200'000;
  spec.run.batches = 16;
  spec.run.threads = static_cast<int>(state.range(0));
  std::uint64_t photons = 0, scatterings = 0;
  for (auto _ : state) {
    const TransportOutput out = run_layered_slab(spec);
    photons += out.photons;
    scatterings += out.scattering_events;
  }
  bench::report_walk(state, photons, scatterings);
}

BENCHMARK_CAPTURE(SlabWalk, sample_analog, "sample.mci", Weighting::analog);
BENCHMARK_CAPTURE(SlabWalk, sample_implicit, "sample.mci", Weighting::implicit_capture);
BENCHMARK_CAPTURE(SlabWalk, skin_analog, "skin.mci", Weighting::analog);
BENCHMARK_CAPTURE(SlabWalk, skin_implicit, "skin.mci", Weighting::implicit_capture);
BENCHMARK_CAPTURE(SlabLanes, sample_analog, "sample.mci", Weighting::analog);
BENCHMARK_CAPTURE(SlabLanes, sample_implicit, "sample.mci", Weighting::implicit_capture);
BENCHMARK_CAPTURE(SlabLanes, skin_analog, "skin.mci", Weighting::analog);
BENCHMARK_CAPTURE(SlabLanes, skin_implicit, "skin.mci", Weighting::implicit_capture);
BENCHMARK_CAPTURE(SlabRun, sample_implicit, "sample.mci", Weighting::implicit_capture)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(SlabRun, skin_implicit, "skin.mci", Weighting::implicit_capture)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace scatterlab
