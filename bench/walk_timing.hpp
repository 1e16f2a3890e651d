#pragma once
// What the walk benchmarks report, one way: photons/s, ns per scattering event (each benchmark
// runs on one thread, so per core) and events per photon; and the timed loop of one kernel's
// RandomWalk over slices of 1000 photons.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

namespace scatterlab::bench {

inline void report_walk(benchmark::State& state, std::uint64_t photons, std::uint64_t scatterings) {
  state.counters["photons/s"] =
      benchmark::Counter(static_cast<double>(photons), benchmark::Counter::kIsRate);
  state.counters["ns/scatter"] =
      benchmark::Counter(static_cast<double>(scatterings) * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["scatters/photon"] =
      photons > 0 ? static_cast<double>(scatterings) / static_cast<double>(photons) : 0.0;
}

// Times `walk` (a RandomWalk) over slices of 1000 photons into one buffer of `cells` values.
template <class Walk>
void time_walk(benchmark::State& state, const Walk& walk, std::size_t cells) {
  auto scratch = walk.make_scratch();
  std::vector<double> buffer(cells, 0.0);
  std::uint64_t photon = 0, scatterings = 0;
  for (auto _ : state) {
    scatterings += walk.run(photon, photon + 1000, buffer.data(), scratch);
    photon += 1000;
  }
  benchmark::DoNotOptimize(buffer.data());
  report_walk(state, photon, scatterings);
}

}  // namespace scatterlab::bench
