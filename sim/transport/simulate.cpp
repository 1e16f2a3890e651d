#include "scatterlab/transport/simulate.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <variant>

#include "scatterlab/core/phase_function.hpp"
#include "scatterlab/tally/batch_statistics.hpp"
#include "scatterlab/tally/scorer.hpp"
#include "scatterlab/transport/random_walk.hpp"

namespace scatterlab {
namespace {

// Photons [first, last) of batch b: the first N mod B batches hold one photon more.
struct BatchRange {
  std::uint64_t first;
  std::uint64_t last;
};

BatchRange batch_range(std::uint64_t photons, std::uint64_t batches, std::uint64_t b) {
  const std::uint64_t base = photons / batches, extra = photons % batches;
  const std::uint64_t first = b * base + std::min(b, extra);
  return {first, first + base + (b < extra ? 1 : 0)};
}

template <class Walk>
SimulationOutput run_batches(const SimulationSpec& spec, const TallyLayout& layout,
                             const Scorer& scorer, const Walk& walk,
                             const ProgressCallback& progress) {
  const std::uint64_t photons = spec.run.photons;
  const std::uint64_t batches = spec.run.batches;
  const int hardware = omp_get_max_threads();
  const int threads = static_cast<int>(std::min<std::uint64_t>(
      batches, static_cast<std::uint64_t>(spec.run.threads > 0 ? spec.run.threads : hardware)));

  BatchStatistics statistics(layout.size);
  // One score buffer per thread: thread t transports batch (round * threads + t).
  std::vector<std::vector<double>> sums(static_cast<std::size_t>(threads),
                                        std::vector<double>(layout.size, 0.0));
  std::vector<std::uint64_t> scatterings(static_cast<std::size_t>(threads), 0);
  const std::uint64_t rounds = (batches + static_cast<std::uint64_t>(threads) - 1) /
                               static_cast<std::uint64_t>(threads);

#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num();
    std::vector<double> crossings = scorer.make_crossing_scratch();
    // Each thread folds its own slice of cells, over the round's batches in batch order.
    const std::size_t slice = (layout.size + static_cast<std::size_t>(threads) - 1) /
                              static_cast<std::size_t>(threads);
    const std::size_t begin = std::min(layout.size, slice * static_cast<std::size_t>(t));
    const std::size_t end = std::min(layout.size, begin + slice);
    for (std::uint64_t round = 0; round < rounds; ++round) {
      const std::uint64_t batch = round * static_cast<std::uint64_t>(threads) +
                                  static_cast<std::uint64_t>(t);
      if (batch < batches) {
        const BatchRange range = batch_range(photons, batches, batch);
        scatterings[static_cast<std::size_t>(t)] +=
            walk.run(range.first, range.last, sums[static_cast<std::size_t>(t)].data(), crossings);
      }
#pragma omp barrier
      for (int k = 0; k < threads; ++k) {
        const std::uint64_t folded = round * static_cast<std::uint64_t>(threads) +
                                     static_cast<std::uint64_t>(k);
        if (folded >= batches) break;
        const BatchRange range = batch_range(photons, batches, folded);
        statistics.add_batch(folded, sums[static_cast<std::size_t>(k)].data(),
                             static_cast<double>(range.last - range.first), begin, end);
      }
#pragma omp barrier
#pragma omp master
      if (progress) progress(static_cast<double>(std::min(batches, (round + 1) * static_cast<std::uint64_t>(threads))) /
                             static_cast<double>(batches));
    }
  }

  SimulationOutput output;
  output.tallies =
      finalize_tallies(spec, layout, statistics.mean(), statistics.standard_error(batches));
  output.photons = photons;
  output.threads = threads;
  for (std::uint64_t s : scatterings) output.scattering_events += s;
  return output;
}

template <class Phase>
SimulationOutput simulate_with(const SimulationSpec& spec, const Phase& phase,
                               const ProgressCallback& progress) {
  const TallyLayout layout(spec);
  const Scorer scorer(spec, layout);
  if (spec.tallies.estimator == Estimator::collision) {
    const RandomWalk<Phase, Estimator::collision> walk(spec, phase, scorer);
    return run_batches(spec, layout, scorer, walk, progress);
  }
  const RandomWalk<Phase, Estimator::track_length> walk(spec, phase, scorer);
  return run_batches(spec, layout, scorer, walk, progress);
}

}  // namespace

SimulationOutput simulate(const SimulationSpec& spec, const ProgressCallback& progress) {
  spec.validate();
  const auto start = std::chrono::steady_clock::now();
  // g = 0 samples isotropically: no HG arithmetic where the scene does not need it.
  SimulationOutput output = spec.medium.g == 0.0
                                ? simulate_with(spec, IsotropicPhase{}, progress)
                                : simulate_with(spec, HenyeyGreenstein{spec.medium.g}, progress);
  output.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return output;
}

}  // namespace scatterlab
