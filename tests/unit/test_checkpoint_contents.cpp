// --resume reads a checkpoint's numbers, not only its fingerprint: a damaged state is refused
// with one error naming the checkpoint and what is wrong, before any batch runs.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/checkpoint_file.hpp"
#include "scatterlab/io/hdf5_file.hpp"

namespace scatterlab {
namespace {

class CheckpointContents : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = std::filesystem::temp_directory_path() /
                 ("scatterlab-checkpoint-contents-" +
                  std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(directory_);
    path_ = directory_ / "run.h5.checkpoint";
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }

  static RunState sound() {
    RunState state;
    state.batches_folded = 3;
    state.scattering_events = 1234;
    state.mean = {0.5, 0.25, 0.0};
    state.squares = {0.01, 0.0, 0.0};
    return state;
  }

  // The error read_checkpoint gives for `state`, or "" when it accepts it.
  std::string refusal(const RunState& state) {
    write_checkpoint(path_, "fingerprint", state);
    try {
      read_checkpoint(path_, "fingerprint");
    } catch (const InputError& error) {
      EXPECT_EQ(error.field(), "--resume");
      EXPECT_NE(std::string(error.what()).find(path_.string()), std::string::npos);
      return error.what();
    }
    return "";
  }

  std::filesystem::path directory_, path_;
};

TEST_F(CheckpointContents, ASoundStateIsRead) {
  EXPECT_EQ(refusal(sound()), "");
}

TEST_F(CheckpointContents, NumbersThatAreNotFiniteAreRefused) {
  RunState state = sound();
  state.mean[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(refusal(state).find("welford_mean[1]"), std::string::npos);
  state = sound();
  state.squares[2] = std::numeric_limits<double>::infinity();
  EXPECT_NE(refusal(state).find("welford_squares[2]"), std::string::npos);
}

TEST_F(CheckpointContents, NegativeSquaresAreRefused) {
  RunState state = sound();
  state.squares[0] = -1e-3;
  EXPECT_NE(refusal(state).find("welford_squares[0]"), std::string::npos);
}

TEST_F(CheckpointContents, OneBatchHasNoSpread) {
  RunState state = sound();
  state.batches_folded = 1;
  EXPECT_NE(refusal(state).find("0 after one batch"), std::string::npos);
  state.squares.assign(3, 0.0);
  EXPECT_EQ(refusal(state), "");
}

TEST_F(CheckpointContents, CountsAndSizesThatCannotBeAreRefused) {
  RunState state = sound();
  state.batches_folded = 0;
  EXPECT_NE(refusal(state).find("batches_folded"), std::string::npos);
  state = sound();
  state.squares.pop_back();
  EXPECT_NE(refusal(state).find("not the same number"), std::string::npos);
  // write_checkpoint cannot store a negative count: the file is changed after it is written.
  write_checkpoint(path_, "fingerprint", sound());
  {
    hdf5::File file = hdf5::File::open_read_write(path_);
    file.root().write_int64_attribute("scattering_events", -5);
    file.close();
  }
  EXPECT_THROW(read_checkpoint(path_, "fingerprint"), InputError);
}

// The run's wall time so far travels with the state, so that a resumed run counts the whole run.
TEST_F(CheckpointContents, WallTimeIsKeptAndAWrongOneRefused) {
  RunState state = sound();
  state.wall_seconds = 12.5;
  write_checkpoint(path_, "fingerprint", state);
  EXPECT_EQ(read_checkpoint(path_, "fingerprint").wall_seconds, 12.5);
  state.wall_seconds = -1.0;
  EXPECT_NE(refusal(state).find("wall_seconds is -1"), std::string::npos);
  state.wall_seconds = std::numeric_limits<double>::infinity();
  EXPECT_NE(refusal(state).find("wall_seconds is inf"), std::string::npos);
}

TEST_F(CheckpointContents, AnotherFormatVersionIsRefused) {
  for (const std::int64_t version : {1, 3}) {
    write_checkpoint(path_, "fingerprint", sound());
    {
      hdf5::File file = hdf5::File::open_read_write(path_);
      file.root().write_int64_attribute("format_version", version);
      file.close();
    }
    try {
      read_checkpoint(path_, "fingerprint");
      FAIL() << "read a checkpoint of format_version " << version;
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find("format_version " + std::to_string(version)),
                std::string::npos);
    }
  }
}

// A checkpoint whose fingerprint matches is still refused when anything it holds was changed
// after it was written, even to values that are sound on their own.
TEST_F(CheckpointContents, AnEditedStateIsRefusedByItsChecksum) {
  const auto edited = [this](auto edit) {
    write_checkpoint(path_, "fingerprint", sound());
    {
      hdf5::File file = hdf5::File::open_read_write(path_);
      edit(file.root());
      file.close();
    }
    try {
      read_checkpoint(path_, "fingerprint");
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string();
  };
  for (const std::string& refusal :
       {edited([](hdf5::Group& root) { root.write_int64_attribute("batches_folded", 4); }),
        edited([](hdf5::Group& root) { root.write_int64_attribute("scattering_events", 1000); }),
        edited([](hdf5::Group& root) { root.write_double_attribute("wall_seconds", 1.0); }),
        edited([](hdf5::Group& root) {
          root.remove_member("welford_mean");
          root.write_dataset("welford_mean", std::vector<double>{0.5, 0.25, 0.125});
        })}) {
    EXPECT_NE(refusal.find("checksum"), std::string::npos) << refusal;
  }
}
}  // namespace
}  // namespace scatterlab
