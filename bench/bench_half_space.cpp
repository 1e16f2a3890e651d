// Cost of the half-space random walk (searchlight): photons/s and ns per scattering event per
// core with the surface tallies on (R_d(r), exitant radiance, totals, split by order), with the
// Fresnel interface off (eta = 1) and on (eta = 1.33), with and without the fluence phi(r, z).
// The infinite-medium kernel's figures for the same media are the Walk/fluence_* rows of
// bench_random_walk.cpp; the iso_albedo0.99 rows here run the same medium for comparison.
//
//   ./build/bench/scatterlab_bench --benchmark_filter=HalfSpace --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <vector>

#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/phase_function.hpp"
#include "scatterlab/tally/scorer.hpp"
#include "scatterlab/tally/tally_book.hpp"
#include "scatterlab/transport/half_space.hpp"
#include "scatterlab/transport/lane_walk.hpp"
#include "scatterlab/transport/random_walk.hpp"
#include "scatterlab/transport/searchlight.hpp"
#include "walk_timing.hpp"

namespace scatterlab {
namespace {

HalfSpaceSpec half_space(double albedo, double g, double eta, bool fluence) {
  HalfSpaceSpec spec;
  spec.medium.albedo = albedo;
  spec.medium.g = g;
  spec.eta = eta;
  spec.tallies.fluence = fluence;
  return spec;
}

template <class Phase, bool fresnel, bool fluence>
void run_walk(benchmark::State& state, const Phase& phase, const HalfSpaceSpec& spec) {
  const TransportProblem problem = transport_problem(spec);
  const TallyBook book(problem.tallies, problem.split_by_order);
  const Scorer scorer(problem.axes, book);
  constexpr Estimator estimator =
      fluence ? Estimator::collision : Estimator::none;
  const RandomWalk<HalfSpace<fresnel>, Phase, estimator> walk(
      HalfSpace<fresnel>(spec.eta), phase, problem.source, scorer, problem.albedo,
      problem.run.escape_radius, problem.run.seed);
  bench::time_walk(state, walk, book.size());
}

// Picks the kernel the scene needs, as the engine does, outside the timed loop.
template <class Phase>
void HalfSpace(benchmark::State& state, Phase phase, HalfSpaceSpec spec) {
  const bool fresnel = spec.eta != 1.0;
  if (fresnel && spec.tallies.fluence) return run_walk<Phase, true, true>(state, phase, spec);
  if (fresnel) return run_walk<Phase, true, false>(state, phase, spec);
  if (spec.tallies.fluence) return run_walk<Phase, false, true>(state, phase, spec);
  run_walk<Phase, false, false>(state, phase, spec);
}

// The same scenes on the lane walk (lane_walk.hpp), which the engine runs for them.
void HalfSpaceLanes(benchmark::State& state, HalfSpaceSpec spec) {
  const TransportProblem problem = transport_problem(spec);
  const TallyBook book(problem.tallies, problem.split_by_order);
  const Scorer scorer(problem.axes, book);
  // (HalfSpace here is the benchmark above; the geometry is scatterlab::HalfSpace.)
  const LaneWalk walk(spec.eta == 1.0 ? LaneGeometry(scatterlab::HalfSpace<false>(spec.eta))
                                      : scatterlab::HalfSpace<true>(spec.eta),
                      scorer, problem.source, problem.albedo, problem.g,
                      spec.tallies.fluence ? Estimator::collision : Estimator::none,
                      problem.run.escape_radius, problem.run.seed);
  bench::time_walk(state, walk, book.size());
  state.counters["lanes"] = LaneWalk::lanes();
}

// The same scene with a declared R(r, t) (transport/declared_tally.hpp), in mm (sigma_t = 1 / mm,
// so the same walk): the engine then runs the walk that keeps each photon's path, and bins its
// exits once more through the filter chain, beside the HalfSpace and HalfSpaceLanes rows.
template <class Phase>
void HalfSpaceTimed(benchmark::State& state, Phase phase, HalfSpaceSpec spec) {
  spec.medium.length_unit = "mm";
  spec.declared_tallies = {{"reflectance_rt",
                            Score::exitance,
                            {{Coordinate::r, 0.0, 10.0, 100}, {Coordinate::t, 0.0, 1e-9, 200}},
                            std::nullopt}};
  const TransportProblem problem = transport_problem(spec);
  const TallyBook book(problem.tallies, problem.split_by_order);
  const Scorer scorer(problem.axes, book);
  const RandomWalk<scatterlab::HalfSpace<true>, Phase, Estimator::none, Weighting::analog, Source,
                   true>
      walk(scatterlab::HalfSpace<true>(spec.eta), phase, problem.source, scorer, problem.albedo,
           problem.run.escape_radius, problem.run.seed);
  bench::time_walk(state, walk, book.size());
}

// The whole run through the batch runner on one thread, as `scatterlab searchlight` does it.
void HalfSpaceWholeRun(benchmark::State& state) {
  HalfSpaceSpec spec = half_space(0.99, 0.0, 1.33, false);
  spec.run.photons = 1'000'000;
  spec.run.threads = 1;
  std::uint64_t photons = 0, scatterings = 0;
  for (auto _ : state) {
    const TransportOutput out = run_half_space(spec);
    photons += out.photons;
    scatterings += out.scattering_events;
  }
  bench::report_walk(state, photons, scatterings);
}

const IsotropicPhase iso{};
const HenyeyGreenstein hg075{0.75};
const HenyeyGreenstein hg09{0.9};

// Isotropic, albedo 0.99: the searchlight default medium.
// Benchmark names are not numbers: the formatter would split hg_g0.9 into hg_g0 .9.
// clang-format off
BENCHMARK_CAPTURE(HalfSpace, iso_albedo0.99_eta1, iso, half_space(0.99, 0.0, 1.0, false));
BENCHMARK_CAPTURE(HalfSpace, iso_albedo0.99_eta1.33, iso, half_space(0.99, 0.0, 1.33, false));
BENCHMARK_CAPTURE(HalfSpace, iso_albedo0.99_eta1.33_fluence, iso, half_space(0.99, 0.0, 1.33, true));
// The semi-infinite medium of MCML's validation (van de Hulst's tables): albedo 0.9, g 0.75.
BENCHMARK_CAPTURE(HalfSpace, hg_g0.75_albedo0.9_eta1, hg075, half_space(0.9, 0.75, 1.0, false));
BENCHMARK_CAPTURE(HalfSpace, hg_g0.75_albedo0.9_eta1.33, hg075, half_space(0.9, 0.75, 1.33, false));
// Forward scattering and long walks: g 0.9, albedo 0.999 (a skin-like reduced albedo 0.99).
BENCHMARK_CAPTURE(HalfSpace, hg_g0.9_albedo0.999_eta1, hg09, half_space(0.999, 0.9, 1.0, false));
BENCHMARK_CAPTURE(HalfSpace, hg_g0.9_albedo0.999_eta1.33, hg09, half_space(0.999, 0.9, 1.33, false));
// MCML's cases a (albedo 0.99, g 0) and b (albedo 0.9, g 0.75), index matched, with the fluence.
BENCHMARK_CAPTURE(HalfSpace, case_a_fluence, iso, half_space(0.99, 0.0, 1.0, true));
BENCHMARK_CAPTURE(HalfSpace, case_b_fluence, hg075, half_space(0.9, 0.75, 1.0, true));
BENCHMARK_CAPTURE(HalfSpaceLanes, case_a_fluence, half_space(0.99, 0.0, 1.0, true));
BENCHMARK_CAPTURE(HalfSpaceLanes, case_b_fluence, half_space(0.9, 0.75, 1.0, true));
BENCHMARK_CAPTURE(HalfSpaceLanes, iso_albedo0.99_eta1, half_space(0.99, 0.0, 1.0, false));
BENCHMARK_CAPTURE(HalfSpaceLanes, iso_albedo0.99_eta1.33, half_space(0.99, 0.0, 1.33, false));
BENCHMARK_CAPTURE(HalfSpaceLanes, iso_albedo0.99_eta1.33_fluence, half_space(0.99, 0.0, 1.33, true));
BENCHMARK_CAPTURE(HalfSpaceLanes, hg_g0.75_albedo0.9_eta1.33, half_space(0.9, 0.75, 1.33, false));
BENCHMARK_CAPTURE(HalfSpaceLanes, hg_g0.9_albedo0.999_eta1.33, half_space(0.999, 0.9, 1.33, false));
BENCHMARK_CAPTURE(HalfSpaceTimed, iso_albedo0.99_eta1.33, iso, half_space(0.99, 0.0, 1.33, false));
BENCHMARK_CAPTURE(HalfSpaceTimed, hg_g0.9_albedo0.999_eta1.33, hg09, half_space(0.999, 0.9, 1.33, false));
BENCHMARK(HalfSpaceWholeRun)->Unit(benchmark::kMillisecond)->UseRealTime();
// clang-format on

}  // namespace
}  // namespace scatterlab
