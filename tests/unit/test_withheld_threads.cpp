// The runner works with whatever team OpenMP grants, and a thread that cannot work ends the run
// with its error, not std::terminate: inside a parallel region an exception may not pass.
#include <gtest/gtest.h>
#include <omp.h>

#include <cstdint>
#include <exception>
#include <new>
#include <vector>

#include "scatterlab/transport/batch_runner.hpp"

namespace scatterlab {
namespace {

// Scores 1 and the photon's index in two cells per photon, one scattering each.
struct IndexWalk {
  int make_scratch() const { return 0; }
  std::uint64_t run(std::uint64_t first, std::uint64_t last, double* sums, int&) const {
    for (std::uint64_t photon = first; photon < last; ++photon) {
      sums[0] += 1.0;
      sums[1] += static_cast<double>(photon);
    }
    return last - first;
  }
};

// The same, but whose working memory cannot be had.
struct RefusedScratchWalk : IndexWalk {
  int make_scratch() const { throw std::bad_alloc(); }
};

// The same, but whose walk throws once it reaches photon `fail_at`.
struct FailingWalk : IndexWalk {
  std::uint64_t fail_at;
  std::uint64_t run(std::uint64_t first, std::uint64_t last, double* sums, int& scratch) const {
    if (last > fail_at) throw std::bad_alloc();
    return IndexWalk::run(first, last, sums, scratch);
  }
};

RunSettings eight_batches(int threads) {
  RunSettings run;
  run.photons = 80'000;
  run.batches = 8;
  run.threads = threads;
  return run;
}

// Runs inside an active parallel region of two threads, where a nested region gets one thread
// (nesting off), as under OMP_THREAD_LIMIT=1 or OMP_DYNAMIC.
template <class Walk>
BatchOutcome run_nested(const RunSettings& run, const Walk& walk) {
  const int levels = omp_get_max_active_levels();
  omp_set_max_active_levels(1);
  BatchOutcome outcome;
  std::exception_ptr failure;  // carried out of the outer region, which no exception may leave
#pragma omp parallel num_threads(2)
  {
#pragma omp single
    try {
      outcome = run_batches(run, 2, walk, {});
    } catch (...) {
      failure = std::current_exception();
    }
  }
  omp_set_max_active_levels(levels);
  if (failure) std::rethrow_exception(failure);
  return outcome;
}

TEST(WithheldThreads, FewerThreadsThanAskedGiveTheSameTallies) {
  const BatchOutcome asked = run_batches(eight_batches(1), 2, IndexWalk{}, {});
  const BatchOutcome withheld = run_nested(eight_batches(4), IndexWalk{});
  EXPECT_EQ(withheld.threads_asked, 4);
  EXPECT_EQ(withheld.threads, 1);  // what it got, not what it asked
  EXPECT_EQ(withheld.batches_done, 8u);
  EXPECT_EQ(withheld.scattering_events, 80'000u);
  ASSERT_EQ(withheld.mean.size(), 2u);
  EXPECT_EQ(withheld.mean, asked.mean);  // bit for bit: batches fold in order on any team
  EXPECT_EQ(withheld.standard_error, asked.standard_error);
  EXPECT_DOUBLE_EQ(withheld.mean[1], (80'000.0 - 1.0) / 2.0);  // the mean photon index
}

TEST(WithheldThreads, WorkingMemoryRefusedIsThrownNotTerminated) {
  EXPECT_THROW(run_batches(eight_batches(2), 2, RefusedScratchWalk{}, {}), std::bad_alloc);
  EXPECT_THROW(run_nested(eight_batches(3), RefusedScratchWalk{}), std::bad_alloc);
}

TEST(WithheldThreads, AWalkThatThrowsEndsTheRunWithItsError) {
  for (const int threads : {1, 2}) {
    FailingWalk walk;
    walk.fail_at = 35'000;  // in the fourth batch
    EXPECT_THROW(run_batches(eight_batches(threads), 2, walk, {}), std::bad_alloc) << threads;
  }
}

}  // namespace
}  // namespace scatterlab
