// Merging runs: pooled batch statistics, checked against one long run and against the pooled
// formula written out by hand; mismatched runs are refused naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/hdf5_file.hpp"
#include "scatterlab/io/merge.hpp"
#include "scatterlab/io/simulation_file.hpp"
#include "scatterlab/tally/batch_statistics.hpp"
#include "scatterlab/tally/pooled_statistics.hpp"
#include "scatterlab/transport/simulate.hpp"

namespace scatterlab {
namespace {

namespace fs = std::filesystem;

TEST(PooledStatistics, TwoHalvesEqualOneSetOfAllBatches) {
  std::mt19937_64 engine(11);
  std::normal_distribution<double> estimate(3.0, 0.5);
  constexpr std::size_t batches = 40;
  std::vector<double> x(batches);
  for (double& value : x) value = estimate(engine);

  // All 40 batches folded in order, as a run does; and 16 + 24 folded apart, then pooled.
  auto fold = [&x](std::size_t first, std::size_t last) {
    BatchStatistics statistics(1);
    for (std::size_t b = first; b < last; ++b) {
      double sum = x[b];
      statistics.add_batch(b - first, &sum, 1.0, 0, 1);
    }
    return statistics;
  };
  const BatchStatistics all = fold(0, batches), a = fold(0, 16), b = fold(16, batches);
  const BatchSet pooled =
      pool({a.mean()[0], a.squares()[0], 16}, {b.mean()[0], b.squares()[0], 24});
  EXPECT_EQ(pooled.batches, 40.0);
  EXPECT_NEAR(pooled.mean, all.mean()[0], 1e-14 * std::abs(all.mean()[0]));
  EXPECT_NEAR(pooled.squares, all.squares()[0], 1e-12 * all.squares()[0]);
  EXPECT_NEAR(pooled.standard_error(), all.standard_error(batches)[0],
              1e-12 * all.standard_error(batches)[0]);

  // From a stored standard error back to the sum of squares.
  const BatchSet stored = BatchSet::from_standard_error(a.mean()[0], a.standard_error(16)[0], 16);
  EXPECT_NEAR(stored.squares, a.squares()[0], 1e-12 * a.squares()[0]);
}

class MergeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() /
                 (std::string("scatterlab-merge-") +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }

  static InfiniteMediumSpec spec(std::uint64_t seed, std::uint32_t batches) {
    InfiniteMediumSpec s;
    s.run.photons = 500ull * batches;
    s.run.batches = batches;
    s.run.seed = seed;
    s.run.threads = 1;
    s.tallies.radiance = false;
    return s;
  }

  fs::path write(const std::string& name, const InfiniteMediumSpec& s,
                 TransportOutput* out = nullptr) {
    const TransportOutput result = run_infinite_medium(s);
    const fs::path path = directory_ / name;
    write_simulation_file(path, s, result.tallies,
                          {"test", "test", iso8601_now(), 1.0, result.photons,
                           result.scattering_events, std::nullopt, 1});
    if (out != nullptr) *out = result;
    return path;
  }

  void expect_refused(const std::vector<fs::path>& inputs, const std::string& field) {
    try {
      merge_simulation_files(inputs, directory_ / "merged.h5", "merge");
      FAIL() << "merged runs that differ in " << field;
    } catch (const InputError& error) {
      EXPECT_EQ(error.field(), field) << error.what();
    }
    EXPECT_FALSE(fs::exists(directory_ / "merged.h5"));
  }

  fs::path directory_;
};

TEST_F(MergeTest, PoolsBatchesAsTheHandFormulaSays) {
  TransportOutput one, two;
  const fs::path a = write("a.h5", spec(1, 4), &one);
  const fs::path b = write("b.h5", spec(2, 6), &two);
  const MergeSummary summary = merge_simulation_files({a, b}, directory_ / "merged.h5", "merge");
  EXPECT_EQ(summary.photons, 5000u);
  EXPECT_EQ(summary.batches, 10u);
  EXPECT_FALSE(summary.unequal_batches);

  const hdf5::File merged = hdf5::File::open_read_only(directory_ / "merged.h5");
  const hdf5::Group& root = merged.root();
  EXPECT_EQ(root.read_int64_attribute("photons_run"), 5000);
  EXPECT_EQ(root.read_int64_attribute("partial"), 0);
  EXPECT_EQ(root.read_string_attribute("merged_from"), a.string() + "\n" + b.string());
  const hdf5::Group parameters = root.open_group("parameters");
  EXPECT_EQ(parameters.read_string_attribute("seeds"), "1,2");
  EXPECT_EQ(parameters.read_int64_attribute("batches"), 10);
  EXPECT_EQ(parameters.read_int64_attribute("photons"), 5000);
  EXPECT_FALSE(parameters.has_attribute("seed"));

  // Pooled mean and M2 = sum_j [M2_j + B_j (m_j - m)^2] over the runs, for every fluence bin.
  const hdf5::Array mean = root.read_dataset("tallies/fluence/mean");
  const hdf5::Array error = root.read_dataset("tallies/fluence/stderr");
  const TallyResult* f1 = nullptr;
  const TallyResult* f2 = nullptr;
  for (std::size_t i = 0; i < one.tallies.size(); ++i) {
    if (one.tallies[i].name == "fluence") f1 = &one.tallies[i], f2 = &two.tallies[i];
  }
  ASSERT_NE(f1, nullptr);
  ASSERT_EQ(mean.values.size(), f1->mean.size());
  std::size_t nonzero = 0;
  for (std::size_t i = 0; i < mean.values.size(); ++i) {
    const double m1 = f1->mean[i], m2 = f2->mean[i];
    const double s1 = f1->stderr_of_mean[i], s2 = f2->stderr_of_mean[i];
    const double m = (4 * m1 + 6 * m2) / 10;
    const double squares =
        s1 * s1 * 4 * 3 + s2 * s2 * 6 * 5 + 4 * (m1 - m) * (m1 - m) + 6 * (m2 - m) * (m2 - m);
    const double expected_error = std::sqrt(squares / (10 * 9));
    EXPECT_NEAR(mean.values[i], m, 1e-13 * std::abs(m) + 1e-300);
    EXPECT_NEAR(error.values[i], expected_error, 1e-11 * expected_error + 1e-300);
    nonzero += m != 0.0;
  }
  EXPECT_GT(nonzero, mean.values.size() / 2);
}

TEST_F(MergeTest, RefusesMismatchedParametersGridsTalliesAndSeeds) {
  const fs::path a = write("a.h5", spec(1, 4));
  InfiniteMediumSpec albedo = spec(2, 4), grid = spec(3, 4), tallies = spec(4, 4);
  albedo.medium.albedo = 0.6;
  grid.grid.z.bins = 20;
  tallies.tallies.flux = false;
  expect_refused({a, write("albedo.h5", albedo)}, "parameters.albedo");
  expect_refused({a, write("grid.h5", grid)}, "grid.z");
  expect_refused({a, write("tallies.h5", tallies)}, "tallies");
  expect_refused({a, write("again.h5", spec(1, 8))}, "parameters.seed");
  expect_refused({a}, "FILES");
}

// Files that agree with the others but not with themselves, or are not whole: refused naming
// FILES, nothing written.
TEST_F(MergeTest, RefusesPartialInconsistentAndUnknownInputs) {
  const fs::path a = write("a.h5", spec(1, 4));
  const InfiniteMediumSpec b = spec(2, 4);
  const TransportOutput out = run_infinite_medium(b);
  const auto written = [&](const std::string& name, std::uint64_t photons,
                           std::optional<std::uint64_t> batches_done) {
    const fs::path path = directory_ / name;
    write_simulation_file(
        path, b, out.tallies,
        {"test", "test", iso8601_now(), 1.0, photons, out.scattering_events, batches_done, 1});
    return path;
  };
  expect_refused({a, written("partial.h5", 1000, 2)}, "FILES");
  expect_refused({a, written("photons.h5", 1999, std::nullopt)}, "FILES");
  const fs::path version = written("version.h5", 2000, std::nullopt);
  {
    hdf5::File file = hdf5::File::open_read_write(version);
    file.root().write_int64_attribute("format_version", kSimulationFormatVersion + 1);
    file.close();
  }
  expect_refused({version, a}, "FILES");
  // The same run, sound, merges.
  EXPECT_NO_THROW(merge_simulation_files({a, written("sound.h5", 2000, std::nullopt)},
                                         directory_ / "merged.h5", "merge"));
}

}  // namespace
}  // namespace scatterlab
