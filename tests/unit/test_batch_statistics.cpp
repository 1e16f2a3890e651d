// Batch statistics: the fold skips blocks of cells that no batch has scored yet, which must leave
// the bits of Welford's update of every cell (written out here) for sparse, signed and dense
// batches, folded whole or in parts as the batch runner's threads fold them.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>
#include <vector>

#include "scatterlab/tally/batch_statistics.hpp"

namespace scatterlab {
namespace {

// Welford's update of every cell, as BatchStatistics documents it.
struct EveryCell {
  std::vector<double> mean, squares;
  explicit EveryCell(std::size_t cells) : mean(cells, 0.0), squares(cells, 0.0) {}
  void add_batch(std::size_t b, const std::vector<double>& sums, double photons) {
    const double per_photon = 1.0 / photons, weight = 1.0 / static_cast<double>(b + 1);
    for (std::size_t i = 0; i < sums.size(); ++i) {
      const double x = sums[i] * per_photon;
      const double delta = x - mean[i];
      mean[i] += delta * weight;
      squares[i] += delta * (x - mean[i]);
    }
  }
};

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::bit_cast<std::uint64_t>(a[i]) != std::bit_cast<std::uint64_t>(b[i])) return false;
  }
  return true;
}

TEST(BatchStatistics, SkippingUnscoredBlocksKeepsTheBitsOfEveryCell) {
  // 1000 cells: 15 full blocks and a partial one. Early batches score a few cells (one block
  // stays unscored until batch 20, and the partial block until batch 30), some with negative
  // scores (a flux); later batches score every cell.
  constexpr std::size_t cells = 1000, batches = 40;
  std::mt19937_64 engine(7);
  std::uniform_int_distribution<std::size_t> cell(0, cells - 1);
  std::normal_distribution<double> score(0.5, 1.0);
  const std::size_t late_block = 5 * BatchStatistics::kBlock,
                    partial = 15 * BatchStatistics::kBlock;

  for (const std::size_t part : {cells, std::size_t{2} * BatchStatistics::kBlock}) {
    BatchStatistics statistics(cells);
    EveryCell reference(cells);
    for (std::size_t b = 0; b < batches; ++b) {
      std::vector<double> sums(cells, 0.0);
      const std::size_t scored = b < 10 ? 3 : b < 35 ? 50 : cells;
      for (std::size_t k = 0; k < scored; ++k) {
        const std::size_t i = scored == cells ? k : cell(engine);
        const bool held_back =
            (i >= late_block && i < late_block + BatchStatistics::kBlock && b < 20) ||
            (i >= partial && b < 30);
        if (!held_back) sums[i] += score(engine);
      }
      const double photons = static_cast<double>(100 + b);
      reference.add_batch(b, sums, photons);
      std::vector<double> buffer = sums;
      for (std::size_t first = 0; first < cells; first += part) {
        statistics.add_batch(b, buffer.data(), photons, first, std::min(cells, first + part));
      }
      EXPECT_EQ(buffer, std::vector<double>(cells, 0.0)) << "batch " << b << " not cleared";
    }
    EXPECT_TRUE(same_bits(statistics.mean(), reference.mean)) << "parts of " << part;
    EXPECT_TRUE(same_bits(statistics.squares(), reference.squares)) << "parts of " << part;
  }
}

// A block scored once and then left at zero is still folded: its mean decays as zeros come in.
TEST(BatchStatistics, AScoredBlockKeepsFoldingZeros) {
  BatchStatistics statistics(2 * BatchStatistics::kBlock);
  std::vector<double> sums(statistics.size(), 0.0);
  sums[3] = 8.0;
  statistics.add_batch(0, sums.data(), 1.0, 0, sums.size());
  for (std::size_t b = 1; b < 4; ++b) statistics.add_batch(b, sums.data(), 1.0, 0, sums.size());
  EXPECT_DOUBLE_EQ(statistics.mean()[3], 2.0);      // 8 / 4
  EXPECT_DOUBLE_EQ(statistics.squares()[3], 48.0);  // 3 * (0 - 2)^2 + (8 - 2)^2
  EXPECT_EQ(statistics.mean()[BatchStatistics::kBlock], 0.0);
}

}  // namespace
}  // namespace scatterlab
