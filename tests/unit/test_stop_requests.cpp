// A stop request is honoured inside a batch, not only between batches, and the run keeps exactly
// the whole groups of batches folded before it, on every rank alike; a state that does not fit the
// run is refused on every rank (none is left waiting).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/transport/batch_runner.hpp"
#include "thread_communicator.hpp"

namespace scatterlab {
namespace {

// Scores one per photon in cell 0 and counts each photon as one scattering; raises `stop` when
// it reaches photon `stop_at` (as a signal would, from outside the runner), once every photon
// below `whole_below` has run (so that the batches before the stop are whole whatever thread runs
// them), and counts the photons it ran after that.
struct CountingWalk {
  std::atomic<bool>* stop;
  std::uint64_t stop_at;
  std::atomic<std::uint64_t>* after_stop;
  std::uint64_t whole_below = 0;
  std::atomic<std::uint64_t>* ran_below = nullptr;

  int make_scratch() const { return 0; }
  std::uint64_t run(std::uint64_t first, std::uint64_t last, double* sums, int&) const {
    for (std::uint64_t photon = first; photon < last; ++photon) {
      if (photon < whole_below) ++*ran_below;
      if (photon == stop_at) {
        while (whole_below > 0 && ran_below->load() < whole_below) std::this_thread::yield();
        stop->store(true);
      }
      if (stop->load()) ++*after_stop;
      sums[0] += 1.0;
      sums[1] += static_cast<double>(photon % 7);
    }
    return last - first;
  }
};

RunSettings four_batches() {
  RunSettings run;
  run.photons = 4'000'000;  // 1e6 per batch: a stop honoured only between batches costs 1e6 more
  run.batches = 4;
  run.threads = 2;
  return run;
}

TEST(StopRequests, HonouredInsideABatchAndTheBatchAbandoned) {
  std::atomic<bool> stop{false};
  std::atomic<std::uint64_t> after_stop{0}, ran_below{0};
  std::vector<std::uint64_t> saved;
  RunControl control;
  control.stop_requested = &stop;
  control.save_checkpoint = [&](const RunState& state) {
    saved.push_back(state.batches_folded);
    EXPECT_EQ(state.scattering_events, 2'000'000u);  // the abandoned batches' are not counted
  };
  // Photon 2.3e6 lies in batch 2; batches 0 and 1 are whole by then, batch 3 is cut or not begun.
  const CountingWalk walk{&stop, 2'300'000, &after_stop, 2'000'000, &ran_below};
  const BatchOutcome out = run_batches(four_batches(), 2, walk, {}, control);
  EXPECT_EQ(out.batches_done, 2u);
  EXPECT_EQ(out.photons_done, 2'000'000u);
  EXPECT_EQ(out.scattering_events, 2'000'000u);
  EXPECT_DOUBLE_EQ(out.mean[0], 1.0);
  EXPECT_EQ(saved, (std::vector<std::uint64_t>{2}));
  // Each thread runs at most one slice of photons once the flag is up.
  EXPECT_LE(after_stop.load(), 2 * detail::kStopPollPhotons);
}

TEST(StopRequests, StoppedInTheFirstBatchHoldsNothingAndSavesNothing) {
  std::atomic<bool> stop{false};
  std::atomic<std::uint64_t> after_stop{0};
  bool saved = false;
  RunControl control;
  control.stop_requested = &stop;
  control.save_checkpoint = [&](const RunState&) { saved = true; };
  const CountingWalk walk{&stop, 10, &after_stop};
  const BatchOutcome out = run_batches(four_batches(), 2, walk, {}, control);
  EXPECT_EQ(out.batches_done, 0u);
  EXPECT_EQ(out.photons_done, 0u);
  EXPECT_EQ(out.scattering_events, 0u);
  EXPECT_FALSE(saved);
}

TEST(StopRequests, EveryRankKeepsTheSameBatchesWhenOneStopsMidBatch) {
  // Only rank 1 sees a stop, inside its batch of the second group; rank 0 finishes its batch.
  // Both must abandon that group.
  std::vector<std::uint64_t> done(2), events(2);
  testing::run_ranks(2, [&](Communicator& communicator) {
    const auto rank = static_cast<std::size_t>(communicator.rank());
    std::atomic<bool> stop{false};
    std::atomic<std::uint64_t> after_stop{0};
    RunSettings run = four_batches();
    run.threads = 1;  // groups of 2 batches, one per rank: batch 3 is rank 1's
    RunControl control;
    control.communicator = &communicator;
    control.stop_requested = &stop;
    const CountingWalk walk{&stop, rank == 1 ? 3'100'000 : run.photons, &after_stop};
    const BatchOutcome out = run_batches(run, 2, walk, {}, control);
    done[rank] = out.batches_done;
    events[rank] = out.scattering_events;
  });
  EXPECT_EQ(done[0], 2u);
  EXPECT_EQ(done[1], 2u);
  EXPECT_EQ(events[0], 2'000'000u);
}

TEST(StopRequests, AStateThatDoesNotFitIsRefusedOnEveryRank) {
  RunState state;
  state.batches_folded = 2;
  state.mean.assign(3, 0.0);  // the run has 2 cells
  state.squares.assign(3, 0.0);
  std::vector<std::string> errors(2);
  testing::run_ranks(2, [&](Communicator& communicator) {
    std::atomic<bool> stop{false};
    std::atomic<std::uint64_t> after_stop{0};
    RunControl control;
    control.communicator = &communicator;
    control.resume_from = &state;
    control.resume_source = "run.h5.checkpoint";
    const CountingWalk walk{&stop, ~std::uint64_t{0}, &after_stop};
    try {
      run_batches(four_batches(), 2, walk, {}, control);
    } catch (const InputError& error) {
      errors[static_cast<std::size_t>(communicator.rank())] = error.what();
    }
  });
  EXPECT_NE(errors[0].find("--resume"), std::string::npos) << errors[0];
  EXPECT_NE(errors[0].find("run.h5.checkpoint"), std::string::npos) << errors[0];
  EXPECT_NE(errors[0].find("3 values"), std::string::npos) << errors[0];
  EXPECT_FALSE(errors[1].empty());

  state.mean.assign(2, 0.0);
  state.squares.assign(2, 0.0);
  state.batches_folded = 5;  // of 4
  RunControl control;
  control.resume_from = &state;
  std::atomic<bool> stop{false};
  std::atomic<std::uint64_t> after_stop{0};
  EXPECT_THROW(run_batches(four_batches(), 2, CountingWalk{&stop, 0, &after_stop}, {}, control),
               InputError);
}

}  // namespace
}  // namespace scatterlab
