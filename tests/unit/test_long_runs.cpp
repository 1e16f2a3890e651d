// Ranks, checkpoints and resuming change no bit of a result: the batch runner's contract.
#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <filesystem>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/checkpoint_file.hpp"
#include "scatterlab/transport/simulate.hpp"
#include "thread_communicator.hpp"

namespace scatterlab {
namespace {

// A small beam: 12 batches, coarse angles; a few tens of milliseconds.
InfiniteMediumSpec small_run(int threads) {
  InfiniteMediumSpec spec;
  spec.run.photons = 12'000;
  spec.run.batches = 12;
  spec.run.seed = 7;
  spec.run.threads = threads;
  spec.grid.theta.bins = 6;
  spec.grid.phi.bins = 8;
  spec.tallies.split_by_order = true;
  return spec;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

void expect_same_tallies(const TransportOutput& expected, const TransportOutput& actual) {
  ASSERT_EQ(expected.tallies.size(), actual.tallies.size());
  for (std::size_t i = 0; i < expected.tallies.size(); ++i) {
    const TallyResult& e = expected.tallies[i];
    const TallyResult& a = actual.tallies[i];
    EXPECT_EQ(e.name, a.name);
    EXPECT_TRUE(same_bits(e.mean, a.mean)) << e.name << " mean";
    EXPECT_TRUE(same_bits(e.stderr_of_mean, a.stderr_of_mean)) << e.name << " stderr";
  }
  EXPECT_EQ(expected.scattering_events, actual.scattering_events);
  EXPECT_EQ(expected.photons, actual.photons);
}

// Runs `spec` on `ranks` threads-as-ranks and returns the root's output.
TransportOutput run_on_ranks(const InfiniteMediumSpec& spec, int ranks,
                             const RunState* resume = nullptr) {
  std::vector<TransportOutput> outputs(static_cast<std::size_t>(ranks));
  testing::run_ranks(ranks, [&](Communicator& communicator) {
    RunControl control;
    control.communicator = &communicator;
    control.resume_from = resume;
    outputs[static_cast<std::size_t>(communicator.rank())] = run_infinite_medium(spec, {}, control);
  });
  for (std::size_t rank = 1; rank < outputs.size(); ++rank) {
    EXPECT_TRUE(outputs[rank].tallies.empty()) << "rank " << rank << " holds tallies";
  }
  return outputs.front();
}

// Stops once `stop_at` of the batches are done and returns the state saved on stopping. On one
// thread the stop is deterministic: the progress after batch k raises the flag, and batch k + 1 is
// cut before its first photon.
RunState interrupted(const InfiniteMediumSpec& spec, double stop_at, TransportOutput* output) {
  std::atomic<bool> stop{false};
  RunState saved;
  RunControl control;
  control.stop_requested = &stop;
  control.save_checkpoint = [&saved](const RunState& state) { saved = state; };
  *output = run_infinite_medium(
      spec, [&](const BatchProgress& done) { stop = stop || done.fraction() >= stop_at; }, control);
  return saved;
}

TEST(DistributedRuns, AnyRanksAndThreadsGiveTheSameBits) {
  const TransportOutput one = run_infinite_medium(small_run(1));
  expect_same_tallies(one, run_infinite_medium(small_run(2)));
  expect_same_tallies(one, run_on_ranks(small_run(1), 2));
  expect_same_tallies(one, run_on_ranks(small_run(2), 2));
  // 3 ranks x 2 threads: groups of 3 batches, ranks owning uneven cell slices.
  const TransportOutput three = run_on_ranks(small_run(2), 3);
  expect_same_tallies(one, three);
  EXPECT_EQ(three.ranks, 3);
  EXPECT_EQ(three.threads, 2);
}

TEST(DistributedRuns, MoreRanksThanBatchesStillFoldEveryBatch) {
  InfiniteMediumSpec spec = small_run(1);
  spec.run.batches = 3;
  expect_same_tallies(run_infinite_medium(spec), run_on_ranks(spec, 4));
}

TEST(Checkpoints, StoppedRunResumesToTheSameBits) {
  const TransportOutput uninterrupted = run_infinite_medium(small_run(2));
  TransportOutput partial;
  const RunState state = interrupted(small_run(1), 0.3, &partial);
  // Progress reports 4 of 12 batches and raises the flag; the runner cuts batch 4 before its
  // first photon and abandons it: 4 batches.
  EXPECT_EQ(partial.batches_done, 4u);
  EXPECT_FALSE(partial.complete(small_run(2)));
  EXPECT_EQ(partial.photons, 4'000u);
  EXPECT_EQ(state.batches_folded, 4u);
  EXPECT_EQ(state.scattering_events, partial.scattering_events);

  // Resumed with another thread count, and on two ranks.
  RunControl control;
  control.resume_from = &state;
  const TransportOutput resumed = run_infinite_medium(small_run(3), {}, control);
  EXPECT_TRUE(resumed.complete(small_run(3)));
  expect_same_tallies(uninterrupted, resumed);
  expect_same_tallies(uninterrupted, run_on_ranks(small_run(1), 2, &state));
}

// A resumed run knows what the earlier run did and how long it took, so that its rates and its
// file count the whole run; its progress says which batches were resumed.
TEST(Checkpoints, ResumedRunCountsTheEarlierRunsWork) {
  TransportOutput partial;
  RunState state = interrupted(small_run(1), 0.3, &partial);
  EXPECT_GT(state.wall_seconds, 0.0);
  EXPECT_LE(state.wall_seconds, partial.wall_seconds);
  state.wall_seconds = 100.0;  // as if the earlier run had been slow
  RunControl control;
  control.resume_from = &state;
  BatchProgress first{};
  const TransportOutput resumed = run_infinite_medium(
      small_run(1),
      [&first](const BatchProgress& done) {
        if (first.batches == 0) first = done;
      },
      control);
  EXPECT_EQ(resumed.photons, 12'000u);
  EXPECT_EQ(resumed.photons_resumed, 4'000u);
  EXPECT_EQ(resumed.session_photons(), 8'000u);
  EXPECT_EQ(resumed.resumed_wall_seconds, 100.0);
  EXPECT_EQ(resumed.run_wall_seconds(), 100.0 + resumed.wall_seconds);
  EXPECT_EQ(first.batches_resumed, 4u);
  EXPECT_EQ(first.photons_resumed, 4'000u);
  EXPECT_EQ(first.batches_done, 5u);  // one batch after the 4 resumed
  EXPECT_EQ(first.photons_done, 5'000u);
}

TEST(Checkpoints, PartialRunIsTheMeanOfItsBatches) {
  InfiniteMediumSpec first_four = small_run(2);
  first_four.run.photons = 4'000;  // batches 0-3 of the 12-batch run, photon for photon
  first_four.run.batches = 4;
  TransportOutput partial;
  interrupted(small_run(1), 0.3, &partial);
  expect_same_tallies(run_infinite_medium(first_four), partial);
}

TEST(Checkpoints, SavedEveryKBatchesButNotAtTheEnd) {
  std::vector<std::uint64_t> saved_at;
  RunControl control;
  control.checkpoint.every_batches = 4;
  control.save_checkpoint = [&](const RunState& state) {
    saved_at.push_back(state.batches_folded);
  };
  const TransportOutput out = run_infinite_medium(small_run(2), {}, control);
  EXPECT_EQ(saved_at, (std::vector<std::uint64_t>{4, 8}));
  expect_same_tallies(run_infinite_medium(small_run(1)), out);
}

TEST(Checkpoints, FailedSaveStopsTheRunWithTheError) {
  RunControl control;
  control.checkpoint.every_batches = 2;
  control.save_checkpoint = [](const RunState&) { throw std::runtime_error("disk full"); };
  EXPECT_THROW(run_infinite_medium(small_run(2), {}, control), std::runtime_error);
}

class CheckpointFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = std::filesystem::temp_directory_path() /
                 ("scatterlab-checkpoint-" +
                  std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(directory_);
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }
  std::filesystem::path directory_;
};

TEST_F(CheckpointFileTest, RoundTripIsExact) {
  TransportOutput partial;
  const RunState state = interrupted(small_run(1), 0.5, &partial);
  const auto path = default_checkpoint_path(directory_ / "run.h5");
  EXPECT_EQ(path.filename(), "run.h5.checkpoint");
  write_checkpoint(path, fingerprint(small_run(2)), state);
  const RunState back = read_checkpoint(path, fingerprint(small_run(2)));
  EXPECT_EQ(back.batches_folded, state.batches_folded);
  EXPECT_EQ(back.scattering_events, state.scattering_events);
  EXPECT_TRUE(same_bits(back.mean, state.mean));
  EXPECT_TRUE(same_bits(back.squares, state.squares));
  // Only the file is left: the temporary was renamed.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(directory_),
                          std::filesystem::directory_iterator()),
            1);
}

TEST_F(CheckpointFileTest, AnotherRunsCheckpointIsRefused) {
  const auto path = directory_ / "run.h5.checkpoint";
  TransportOutput partial;
  write_checkpoint(path, fingerprint(small_run(2)), interrupted(small_run(1), 0.5, &partial));
  InfiniteMediumSpec other_seed = small_run(2);
  other_seed.run.seed = 8;
  try {
    read_checkpoint(path, fingerprint(other_seed));
    FAIL() << "accepted a checkpoint of another seed";
  } catch (const InputError& error) {
    EXPECT_EQ(error.field(), "--resume");
    EXPECT_NE(std::string(error.what()).find("other parameters or seed"), std::string::npos);
  }
  EXPECT_THROW(read_checkpoint(directory_ / "missing", fingerprint(small_run(2))), InputError);
}

TEST(Fingerprint, NamesTheRunNotHowItRan) {
  const std::string base = fingerprint(small_run(1));
  EXPECT_EQ(base.size(), 16u);
  EXPECT_EQ(base, fingerprint(small_run(4)));  // threads never change a result
  InfiniteMediumSpec seed = small_run(1), albedo = small_run(1), bins = small_run(1);
  seed.run.seed = 8;
  albedo.medium.albedo = 0.5000000001;
  bins.grid.r.bins = 16;
  EXPECT_NE(base, fingerprint(seed));
  EXPECT_NE(base, fingerprint(albedo));
  EXPECT_NE(base, fingerprint(bins));
}

}  // namespace
}  // namespace scatterlab
