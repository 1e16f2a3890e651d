#pragma once
// Runs photons in independent, seeded batches over threads and folds every tally cell into batch
// statistics. Shared by every random-walk kernel (infinite medium, half-space, ...): a kernel
// only says how to transport photons [first, last) into a buffer of per-cell sums.
//
// Results are bitwise identical for any thread count: each photon's random stream depends only
// on (seed, photon index), each batch is transported by one thread in photon order, and batches
// are folded into the statistics in batch order.

#include <omp.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "scatterlab/tally/batch_statistics.hpp"
#include "scatterlab/transport/run_settings.hpp"

namespace scatterlab {

// Called on the calling thread with the fraction of batches done, in [0, 1].
using ProgressCallback = std::function<void(double fraction_done)>;

// Photons [first, last) of batch b: the first N mod B batches hold one photon more.
struct BatchRange {
  std::uint64_t first;
  std::uint64_t last;
};

inline BatchRange batch_range(std::uint64_t photons, std::uint64_t batches, std::uint64_t b) {
  const std::uint64_t base = photons / batches, extra = photons % batches;
  const std::uint64_t first = b * base + std::min(b, extra);
  return {first, first + base + (b < extra ? 1 : 0)};
}

struct BatchOutcome {
  std::vector<double> mean;            // per photon, for every tally cell
  std::vector<double> standard_error;  // of that mean, from the batch-to-batch spread
  std::uint64_t scattering_events = 0;
  int threads = 1;
};

// `Walk` provides
//   Scratch make_scratch() const;        per-thread working memory, made once per thread
//   std::uint64_t run(std::uint64_t first, std::uint64_t last, double* sums, Scratch&) const;
// where run adds the scores of photons [first, last) to sums[0, cells) and returns the number
// of scattering events.
template <class Walk>
BatchOutcome run_batches(const RunSettings& run, std::size_t cells, const Walk& walk,
                         const ProgressCallback& progress) {
  const std::uint64_t photons = run.photons;
  const std::uint64_t batches = run.batches;
  const int hardware = omp_get_max_threads();
  const int threads = static_cast<int>(std::min<std::uint64_t>(
      batches, static_cast<std::uint64_t>(run.threads > 0 ? run.threads : hardware)));
  const auto thread_count = static_cast<std::uint64_t>(threads);

  BatchStatistics statistics(cells);
  // One score buffer per thread: thread t transports batch (round * threads + t).
  std::vector<std::vector<double>> sums(static_cast<std::size_t>(threads),
                                        std::vector<double>(cells, 0.0));
  std::vector<std::uint64_t> scatterings(static_cast<std::size_t>(threads), 0);
  const std::uint64_t rounds = (batches + thread_count - 1) / thread_count;

#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num();
    auto scratch = walk.make_scratch();
    // Each thread folds its own slice of cells, over the round's batches in batch order.
    const std::size_t slice = (cells + static_cast<std::size_t>(threads) - 1) /
                              static_cast<std::size_t>(threads);
    const std::size_t begin = std::min(cells, slice * static_cast<std::size_t>(t));
    const std::size_t end = std::min(cells, begin + slice);
    for (std::uint64_t round = 0; round < rounds; ++round) {
      const std::uint64_t batch = round * thread_count + static_cast<std::uint64_t>(t);
      if (batch < batches) {
        const BatchRange range = batch_range(photons, batches, batch);
        scatterings[static_cast<std::size_t>(t)] +=
            walk.run(range.first, range.last, sums[static_cast<std::size_t>(t)].data(), scratch);
      }
#pragma omp barrier
      for (int k = 0; k < threads; ++k) {
        const std::uint64_t folded = round * thread_count + static_cast<std::uint64_t>(k);
        if (folded >= batches) break;
        const BatchRange range = batch_range(photons, batches, folded);
        statistics.add_batch(folded, sums[static_cast<std::size_t>(k)].data(),
                             static_cast<double>(range.last - range.first), begin, end);
      }
#pragma omp barrier
#pragma omp master
      if (progress) {
        progress(static_cast<double>(std::min(batches, (round + 1) * thread_count)) /
                 static_cast<double>(batches));
      }
    }
  }

  BatchOutcome outcome;
  outcome.mean = statistics.mean();
  outcome.standard_error = statistics.standard_error(batches);
  outcome.threads = threads;
  for (std::uint64_t s : scatterings) outcome.scattering_events += s;
  return outcome;
}

}  // namespace scatterlab
