// Batches are dealt to threads as they become free and folded in batch order: the statistics are
// the same bits for any thread and rank count, and a batch held back does not hold back the
// others (they run ahead as far as the ring of score buffers allows).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <thread>
#include <vector>

#include "scatterlab/transport/batch_runner.hpp"
#include "thread_communicator.hpp"

namespace scatterlab {
namespace {

// Scores values that differ from photon to photon in every cell, so that folding batches in
// another order, or a batch twice, changes the last bits.
struct ScrambledWalk {
  static constexpr std::size_t kCells = 5;

  int make_scratch() const { return 0; }
  std::uint64_t run(std::uint64_t first, std::uint64_t last, double* sums, int&) const {
    for (std::uint64_t photon = first; photon < last; ++photon) {
      for (std::size_t c = 0; c < kCells; ++c) {
        sums[c] += std::sin(0.37 * static_cast<double>(photon) + static_cast<double>(c));
      }
    }
    return last - first;
  }
};

// Scores a few cells per photon, scattered over a tally of several fold parts
// (detail::kFoldPart cells each), so that waiting threads fold parts of it.
struct WideWalk {
  static constexpr std::size_t kCells = 3 * detail::kFoldPart + 17;

  int make_scratch() const { return 0; }
  std::uint64_t run(std::uint64_t first, std::uint64_t last, double* sums, int&) const {
    for (std::uint64_t photon = first; photon < last; ++photon) {
      for (std::uint64_t j = 0; j < 8; ++j) {
        sums[(photon * 7919 + j * 104729) % kCells] += std::sin(0.37 * static_cast<double>(photon));
      }
    }
    return last - first;
  }
};

RunSettings thirteen_batches(int threads) {
  RunSettings run;
  run.photons = 20'011;
  run.batches = 13;
  run.threads = threads;
  return run;
}

template <class Walk>
void expect_same_bits_for_any_thread_and_rank_count() {
  const BatchOutcome one = run_batches(thirteen_batches(1), Walk::kCells, Walk{}, {});
  ASSERT_EQ(one.batches_done, 13u);
  for (const int threads : {2, 3, 5, 8, 13}) {
    const BatchOutcome many = run_batches(thirteen_batches(threads), Walk::kCells, Walk{}, {});
    EXPECT_EQ(many.mean, one.mean) << threads << " threads";
    EXPECT_EQ(many.standard_error, one.standard_error) << threads << " threads";
    EXPECT_EQ(many.scattering_events, one.scattering_events);
  }
  for (const int ranks : {2, 3}) {
    for (const int threads : {1, 2}) {
      std::vector<double> mean, error;
      testing::run_ranks(ranks, [&](Communicator& communicator) {
        RunControl control;
        control.communicator = &communicator;
        const BatchOutcome out =
            run_batches(thirteen_batches(threads), Walk::kCells, Walk{}, {}, control);
        if (communicator.is_root()) {
          mean = out.mean;
          error = out.standard_error;
        }
      });
      EXPECT_EQ(mean, one.mean) << ranks << " ranks of " << threads << " threads";
      EXPECT_EQ(error, one.standard_error) << ranks << " ranks of " << threads << " threads";
    }
  }
}

TEST(BatchDealing, SameBitsForAnyThreadAndRankCount) {
  expect_same_bits_for_any_thread_and_rank_count<ScrambledWalk>();
}

// Folded in parts by several threads: each cell's arithmetic is the same whoever folds it.
TEST(BatchDealing, SameBitsWhenFoldedInParts) {
  expect_same_bits_for_any_thread_and_rank_count<WideWalk>();
}

// Holds batch 0 until the photons of batches 1 to `ahead` have run (or `patience` has passed),
// as a descheduled thread would.
struct HeldWalk {
  std::uint64_t per_batch;
  std::uint64_t ahead;
  std::atomic<std::uint64_t>* ran_ahead;
  std::atomic<bool>* gave_up;

  int make_scratch() const { return 0; }
  std::uint64_t run(std::uint64_t first, std::uint64_t last, double* sums, int& scratch) const {
    const std::uint64_t target = ahead * per_batch;
    if (first == 0) {
      const auto patience = std::chrono::steady_clock::now() + std::chrono::seconds(20);
      while (ran_ahead->load() < target) {
        if (std::chrono::steady_clock::now() > patience) {
          gave_up->store(true);
          break;
        }
        std::this_thread::yield();
      }
    } else if (first < (ahead + 1) * per_batch) {
      *ran_ahead += last - first;
    }
    return ScrambledWalk{}.run(first, last, sums, scratch);
  }
};

TEST(BatchDealing, AHeldBatchDoesNotHoldTheOthers) {
  // Three threads hold a ring of five buffers: while batch 0 is held, the other two threads run
  // batches 1 to 4 (batch 5 waits for batch 0's buffer to be folded).
  RunSettings run;
  run.batches = 8;
  run.photons = 8 * 1000;
  run.threads = 3;
  std::atomic<std::uint64_t> ran_ahead{0};
  std::atomic<bool> gave_up{false};
  const BatchOutcome held =
      run_batches(run, ScrambledWalk::kCells, HeldWalk{1000, 4, &ran_ahead, &gave_up}, {});
  EXPECT_FALSE(gave_up.load()) << "batches 1 to 4 waited for batch 0";
  EXPECT_EQ(ran_ahead.load(), 4000u);
  const BatchOutcome free = run_batches(run, ScrambledWalk::kCells, ScrambledWalk{}, {});
  EXPECT_EQ(held.mean, free.mean);
  EXPECT_EQ(held.standard_error, free.standard_error);
}

TEST(BatchDealing, TheRingHoldsTwoBuffersPerThreadButOne) {
  EXPECT_EQ(score_buffers(1, 64, 1), 1u);
  EXPECT_EQ(score_buffers(2, 64, 1), 3u);
  EXPECT_EQ(score_buffers(16, 64, 1), 31u);
  EXPECT_EQ(score_buffers(8, 8, 1), 8u);   // never more than the batches
  EXPECT_EQ(score_buffers(4, 13, 3), 5u);  // nor than a rank's groups
}

}  // namespace
}  // namespace scatterlab
