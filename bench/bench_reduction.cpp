// The cost of folding batches into statistics (every cell scored, or a few) and of clearing a
// batch's buffer once it is sent to the other ranks (batch_runner.hpp), per batch, for the default
// grid and a fine radiance grid.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <vector>

#include "scatterlab/tally/batch_statistics.hpp"
#include "scatterlab/tally/tally_book.hpp"
#include "scatterlab/transport/simulate.hpp"

namespace {

using scatterlab::InfiniteMediumSpec;

// 0: the default grid (15 x 40 x 18 x 36 radiance); 1: a fine one (60 x 160 x 36 x 72).
std::size_t cells_of(int grid) {
  InfiniteMediumSpec spec;
  if (grid == 1) {
    spec.grid.r.bins = 60;
    spec.grid.z.bins = 160;
    spec.grid.theta.bins = 36;
    spec.grid.phi.bins = 72;
  }
  const scatterlab::TransportProblem problem = scatterlab::transport_problem(spec);
  return scatterlab::TallyBook(problem.tallies, problem.split_by_order).size();
}

// Folds one batch an iteration, `score` filling its sums first (each fold clears them).
template <class Score>
void fold_batches(benchmark::State& state, std::vector<double>& sums, double photons,
                  const Score& score) {
  scatterlab::BatchStatistics statistics(sums.size());
  std::size_t batch = 0;
  for (auto _ : state) {
    score(sums);
    statistics.add_batch(batch++, sums.data(), photons, 0, sums.size());
    benchmark::DoNotOptimize(statistics.mean().data());
  }
  state.counters["cells"] = static_cast<double>(sums.size());
}

// One batch folded into every cell: the work the folding side does per batch.
void BM_FoldBatch(benchmark::State& state) {
  const std::size_t cells = cells_of(static_cast<int>(state.range(0)));
  std::vector<double> sums(cells, 1.0);
  fold_batches(state, sums, 1000.0, [](std::vector<double>&) {});
  state.counters["ns_per_cell"] =
      benchmark::Counter(static_cast<double>(cells), benchmark::Counter::kIsIterationInvariantRate |
                                                         benchmark::Counter::kInvert);
}
BENCHMARK(BM_FoldBatch)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// A batch of a short run: 200 scored cells (100 photons of the default scene score about that
// many), the same ones in every batch; the blocks no batch has scored are only read.
void BM_FoldSparseBatch(benchmark::State& state) {
  std::vector<double> sums(cells_of(static_cast<int>(state.range(0))), 0.0);
  fold_batches(state, sums, 2.0, [](std::vector<double>& batch) {
    for (std::size_t k = 0; k < 200; ++k) batch[k * (batch.size() / 200)] = 1.0;
  });
}
BENCHMARK(BM_FoldSparseBatch)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// Clearing a batch's buffer after the exchange sent it (under MPI; on one rank folding clears it).
void BM_ClearBatch(benchmark::State& state) {
  const std::size_t cells = cells_of(static_cast<int>(state.range(0)));
  std::vector<double> sums(cells, 1.0);
  for (auto _ : state) {
    std::fill(sums.begin(), sums.end(), 0.0);
    benchmark::DoNotOptimize(sums.data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * cells * sizeof(double)));
}
BENCHMARK(BM_ClearBatch)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
