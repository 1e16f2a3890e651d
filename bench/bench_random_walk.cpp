// Cost of the infinite-medium random walk: photons/s and ns per scattering event per core, for
// (g = 0.9, albedo 0.5) and (g = 0, albedo 0.99), with the
// fluence tallies alone and with the full radiance tally, on the one-photon RandomWalk (Walk)
// and on the lane walk the engine runs (Lanes), next to a bare loop that only draws the random
// numbers and samples free paths and directions (the one-photon ceiling) and the lane walk with
// no tally (LaneLoop, the lanes' ceiling), and the whole multi-threaded run on 1, 2, 3 and 8
// threads.
//
//   ./build/bench/scatterlab_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <cmath>

#include "scatterlab/core/phase_function.hpp"
#include "scatterlab/core/random.hpp"
#include "scatterlab/tally/scorer.hpp"
#include "scatterlab/tally/tally_book.hpp"
#include "scatterlab/transport/infinite_medium.hpp"
#include "scatterlab/transport/lane_walk.hpp"
#include "scatterlab/transport/random_walk.hpp"
#include "scatterlab/transport/simulate.hpp"
#include "walk_timing.hpp"

namespace scatterlab {
namespace {

InfiniteMediumSpec scene(double g, double albedo, bool radiance, Estimator estimator) {
  InfiniteMediumSpec spec;
  spec.medium.g = g;
  spec.medium.albedo = albedo;
  spec.tallies.radiance = radiance;
  spec.tallies.estimator = estimator;
  return spec;
}

// The ceiling: per event one Philox call, a free path, an HG cosine, an azimuth and a frame
// rotation (at g = 0 a direction drawn afresh, as the walk does); no tallies, no positions.
template <class Phase>
void BareLoop(benchmark::State& state, Phase phase, double albedo) {
  std::uint64_t photon = 0, scatterings = 0, photons = 0;
  double sink = 0.0;
  for (auto _ : state) {
    for (int i = 0; i < 1000; ++i, ++photon) {
      PhotonRandom random(1, photon);
      Vec3 direction = Vec3::UnitZ();
      for (;;) {
        const auto u = random.next4();
        sink += -std::log(u[0]);
        if (u[1] >= albedo) break;
        direction = scattered_direction(phase, direction, u[2], u[3]);  // as the walk draws it
        ++scatterings;
      }
      sink += direction.z();
    }
    photons += 1000;
  }
  benchmark::DoNotOptimize(sink);
  bench::report_walk(state, photons, scatterings);
}

template <class Phase, Estimator estimator>
void run_walk(benchmark::State& state, const Phase& phase, const InfiniteMediumSpec& spec) {
  const TransportProblem problem = transport_problem(spec);
  const TallyBook book(problem.tallies, problem.split_by_order);
  const Scorer scorer(problem.axes, book);
  const RandomWalk<InfiniteMedium, Phase, estimator> walk(
      InfiniteMedium{}, phase, problem.source, scorer, problem.albedo, problem.run.escape_radius,
      problem.run.seed);
  std::vector<double> buffer(book.size(), 0.0);
  std::vector<double> crossings = walk.make_scratch();
  std::uint64_t photon = 0, scatterings = 0;
  for (auto _ : state) {
    scatterings += walk.run(photon, photon + 1000, buffer.data(), crossings);
    photon += 1000;
  }
  benchmark::DoNotOptimize(buffer.data());
  bench::report_walk(state, photon, scatterings);
}

// Picks the kernel the scene needs, as the engine does, outside the timed loop.
template <class Phase>
void Walk(benchmark::State& state, Phase phase, InfiniteMediumSpec spec) {
  if (spec.tallies.estimator == Estimator::collision) {
    run_walk<Phase, Estimator::collision>(state, phase, spec);
  } else {
    run_walk<Phase, Estimator::track_length>(state, phase, spec);
  }
}

// The same scenes on the lane walk (lane_walk.hpp), which the engine runs for them; `lanes` in
// the counters is the vector width the machine's instruction set gives.
void Lanes(benchmark::State& state, InfiniteMediumSpec spec) {
  const TransportProblem problem = transport_problem(spec);
  const TallyBook book(problem.tallies, problem.split_by_order);
  const Scorer scorer(problem.axes, book);
  const LaneWalk walk(InfiniteMedium{}, scorer, problem.source, problem.albedo, problem.g,
                      Estimator::collision, problem.run.escape_radius, problem.run.seed);
  bench::time_walk(state, walk, book.size());
  state.counters["lanes"] = LaneWalk::lanes();
}

// The lane walk's ceiling: its loop with no tally at all (no volume estimator, no declared score),
// beside BareLoop, the one-photon ceiling.
void LaneLoop(benchmark::State& state, InfiniteMediumSpec spec) {
  TransportProblem problem = transport_problem(spec);
  problem.tallies.clear();
  const TallyBook book(problem.tallies, false);
  const Scorer scorer(problem.axes, book);
  const LaneWalk walk(InfiniteMedium{}, scorer, problem.source, problem.albedo, problem.g,
                      Estimator::none, problem.run.escape_radius, problem.run.seed);
  bench::time_walk(state, walk, book.size());
  state.counters["lanes"] = LaneWalk::lanes();
}

void WholeRun(benchmark::State& state) {
  InfiniteMediumSpec spec = scene(0.9, 0.5, true, Estimator::collision);
  spec.run.photons = 10'000'000;  // batches of ~1.5e5 photons, as in the default job's regime
  spec.run.threads = static_cast<int>(state.range(0));
  std::uint64_t photons = 0, scatterings = 0;
  for (auto _ : state) {
    const TransportOutput out = run_infinite_medium(spec);
    photons += out.photons;
    scatterings += out.scattering_events;
  }
  bench::report_walk(state, photons, scatterings);
}

const HenyeyGreenstein forward{0.9};
const IsotropicPhase isotropic{};

// Benchmark names are not numbers: the formatter would split hg_g0.9 into hg_g0 .9.
// clang-format off
BENCHMARK_CAPTURE(BareLoop, hg_g0.9_albedo0.5, forward, 0.5);
BENCHMARK_CAPTURE(BareLoop, iso_albedo0.99, isotropic, 0.99);
BENCHMARK_CAPTURE(Walk, fluence_hg_g0.9_albedo0.5, forward, scene(0.9, 0.5, false, Estimator::collision));
BENCHMARK_CAPTURE(Walk, radiance_hg_g0.9_albedo0.5, forward, scene(0.9, 0.5, true, Estimator::collision));
BENCHMARK_CAPTURE(Walk, fluence_iso_albedo0.99, isotropic, scene(0.0, 0.99, false, Estimator::collision));
BENCHMARK_CAPTURE(Walk, radiance_iso_albedo0.99, isotropic, scene(0.0, 0.99, true, Estimator::collision));
BENCHMARK_CAPTURE(Walk, track_fluence_hg_g0.9_albedo0.5, forward, scene(0.9, 0.5, false, Estimator::track_length));
BENCHMARK_CAPTURE(Walk, track_radiance_hg_g0.9_albedo0.5, forward, scene(0.9, 0.5, true, Estimator::track_length));
BENCHMARK_CAPTURE(LaneLoop, hg_g0.9_albedo0.5, scene(0.9, 0.5, false, Estimator::collision));
BENCHMARK_CAPTURE(LaneLoop, iso_albedo0.99, scene(0.0, 0.99, false, Estimator::collision));
BENCHMARK_CAPTURE(Lanes, fluence_hg_g0.9_albedo0.5, scene(0.9, 0.5, false, Estimator::collision));
BENCHMARK_CAPTURE(Lanes, radiance_hg_g0.9_albedo0.5, scene(0.9, 0.5, true, Estimator::collision));
BENCHMARK_CAPTURE(Lanes, fluence_iso_albedo0.99, scene(0.0, 0.99, false, Estimator::collision));
BENCHMARK_CAPTURE(Lanes, radiance_iso_albedo0.99, scene(0.0, 0.99, true, Estimator::collision));
// More threads than cores (on a 2-core machine: 3 and 8) stand for threads that the system
// deschedules: dealt as they come free, batches keep the cores' throughput.
BENCHMARK(WholeRun)->Arg(1)->Arg(2)->Arg(3)->Arg(8)->Unit(benchmark::kMillisecond)->UseRealTime();
// clang-format on

}  // namespace
}  // namespace scatterlab

BENCHMARK_MAIN();
