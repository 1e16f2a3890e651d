// The limits every command holds its values to, one check each: thread counts and
// seeds (transport/run_settings.hpp), the span of a grid's length axes in mfp
// (transport/length_units.hpp), scene files (io/text_file.hpp) and the last guard before a tally
// reaches a file (io/simulation_file.hpp).
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <omp.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "input_error_field.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/io/simulation_file.hpp"
#include "scatterlab/io/text_file.hpp"
#include "scatterlab/transport/length_units.hpp"
#include "scatterlab/transport/run_settings.hpp"
#include "scatterlab/transport/searchlight.hpp"
#include "scatterlab/transport/simulation.hpp"

namespace scatterlab {
namespace {

namespace fs = std::filesystem;

using test_support::field_of;

TEST(ValueLimits, ThreadsUpToFourPerHardwareThread) {
  EXPECT_GE(max_threads(), 4);
  EXPECT_EQ(field_of([] { check_threads(0, "--threads"); }), "");
  EXPECT_EQ(field_of([] { check_threads(1, "--threads"); }), "");
  EXPECT_EQ(field_of([] { check_threads(max_threads(), "--threads"); }), "");
  EXPECT_EQ(field_of([] { check_threads(max_threads() + 1, "--threads"); }), "--threads");
  EXPECT_EQ(field_of([] { check_threads(100000, "--threads"); }), "--threads");
  EXPECT_EQ(field_of([] { check_threads(-1, "--threads"); }), "--threads");
  try {
    check_threads(100000, "--threads");
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fmt::format("[0, {}]", max_threads())), std::string::npos)
        << e.what();
  }
}

TEST(ValueLimits, ZeroThreadsHoldsOpenMPsCountToTheSameBound) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(max_threads() + 1);  // as OMP_NUM_THREADS would
  const std::string field = field_of([] { check_threads(0, "--threads"); });
  omp_set_num_threads(before);
  EXPECT_EQ(field, "OMP_NUM_THREADS");
  EXPECT_EQ(field_of([] { check_threads(0, "--threads"); }), "");
}

TEST(ValueLimits, RunSettingsUseTheSameChecks) {
  RunSettings run;
  run.threads = max_threads() + 1;
  EXPECT_EQ(field_of([&] { check_run_settings(run); }), "run.threads");
  run.threads = 0;
  run.seed = max_seed + 1;
  EXPECT_EQ(field_of([&] { check_run_settings(run); }), "run.seed");
  run.seed = max_seed;
  EXPECT_EQ(field_of([&] { check_run_settings(run); }), "");
}

TEST(ValueLimits, SeedsAreWhatATomlIntegerHolds) {
  EXPECT_EQ(field_of([] { check_seed(0, "--seed"); }), "");
  EXPECT_EQ(field_of([] { check_seed(max_seed, "--seed"); }), "");
  EXPECT_EQ(field_of([] { check_seed(max_seed + 1, "--seed"); }), "--seed");
  EXPECT_EQ(field_of([] { check_seed(std::numeric_limits<std::uint64_t>::max(), "--seed"); }),
            "--seed");
  // A command running 7 seeds from --seed upward: the last must be in range too.
  EXPECT_EQ(field_of([] { check_seed(max_seed - 6, "--seed", 7); }), "");
  EXPECT_EQ(field_of([] { check_seed(max_seed - 5, "--seed", 7); }), "--seed");
}

TEST(ValueLimits, GridsWhoseBinsUnderflowOrOverflowAreRefused) {
  InfiniteMediumSpec spec;
  EXPECT_EQ(field_of([&] { spec.validate(); }), "");
  spec.grid.r.max = 1e-300;  // rings of zero area: NaN fluence
  EXPECT_EQ(field_of([&] { spec.validate(); }), "grid.r.max");
  spec.grid.r.max = 1e13;
  EXPECT_EQ(field_of([&] { spec.validate(); }), "grid.r.max");
  spec = InfiniteMediumSpec{};
  spec.grid.z.min = -1e308;  // bins of infinite width
  spec.grid.z.max = 1e308;
  EXPECT_EQ(field_of([&] { spec.validate(); }), "grid.z.min");
  spec = InfiniteMediumSpec{};
  spec.grid.rho.max = 1e-200;  // shells of zero volume
  EXPECT_EQ(field_of([&] { spec.validate(); }), "grid.rho.max");

  HalfSpaceSpec half;
  EXPECT_EQ(field_of([&] { half.validate(); }), "");
  half.grid.r.max = 1e-300;
  EXPECT_EQ(field_of([&] { half.validate(); }), "grid.r.max");
  half = HalfSpaceSpec{};
  half.grid.z.max = 1e300;
  EXPECT_EQ(field_of([&] { half.validate(); }), "grid.z.max");
}

TEST(ValueLimits, TheSpanIsInMeanFreePaths) {
  // 1 mm at sigma_t = 1e-12 / mm is 1e-12 mfp: 15 bins of it are too narrow; at 1 / mm it is fine.
  const UniformAxis r{0.0, 1.0, 15};
  EXPECT_EQ(field_of([&] {
              check_length_axis_span(r, "r", Medium{0.5, 1e-12, 0.0, "mm"});
            }),
            "grid.r.max");
  EXPECT_EQ(field_of([&] { check_length_axis_span(r, "r", Medium{0.5, 1.0, 0.0, "mm"}); }), "");
  EXPECT_EQ(field_of([&] {
              check_length_axis_span(r, "r", Medium{0.5, 1e13, 0.0, "mm"});
            }),
            "grid.r.max");
}

TEST(ValueLimits, AnEscapeRadiusThatOverflowsInMfpIsRefused) {
  const Medium mm{1.0, 1e10, 0.0, "mm"};
  EXPECT_EQ(field_of([&] { check_escape_radius_span(1e300, mm); }), "run.escape_radius");
  EXPECT_EQ(field_of([&] { check_escape_radius_span(1e290, mm); }), "");
  EXPECT_EQ(field_of([&] { check_escape_radius_span(HUGE_VAL, mm); }), "");  // none: inf
  InfiniteMediumSpec spec;
  spec.medium = Medium{1.0, 1e10, 0.0, "mm"};
  spec.run.escape_radius = 1e300;
  EXPECT_EQ(field_of([&] { spec.validate(); }), "run.escape_radius");
}

class SceneFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() / ("scatterlab-scene-files-" + std::to_string(::getpid()) + "-" +
                                     std::to_string(reinterpret_cast<std::uintptr_t>(this)));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(SceneFiles, OnlySmallRegularFiles) {
  const fs::path scene = dir_ / "scene.toml";
  std::ofstream(scene) << "[medium]\nalbedo = 0.5\n";
  EXPECT_EQ(read_scene_file(scene, "--scene"), "[medium]\nalbedo = 0.5\n");
  EXPECT_EQ(field_of([&] { check_scene_file(dir_, "--scene"); }), "--scene");
  EXPECT_EQ(field_of([&] { check_scene_file(dir_ / "none.toml", "--scene"); }), "--scene");
  EXPECT_EQ(field_of([&] { check_scene_file("/dev/urandom", "--scene"); }), "--scene");
  const fs::path fifo = dir_ / "fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(field_of([&] { read_scene_file(fifo, "--scene"); }), "--scene");  // never opened
  const fs::path big = dir_ / "big.toml";
  std::ofstream(big) << std::string(max_scene_bytes + 1, '#');
  EXPECT_EQ(field_of([&] { read_scene_file(big, "--scene"); }), "--scene");
  const fs::path limit = dir_ / "limit.toml";
  std::ofstream(limit) << std::string(max_scene_bytes, '#');
  EXPECT_EQ(read_scene_file(limit, "--scene").size(), max_scene_bytes);
}

TEST(ValueLimits, NonFiniteTalliesAreNotWritten) {
  EXPECT_NO_THROW(check_finite_tally("fluence", {1.0, 0.0}, {0.1, 0.0}));
  EXPECT_THROW(check_finite_tally("fluence", {1.0, std::nan("")}, {0.1, 0.0}), std::runtime_error);
  EXPECT_THROW(check_finite_tally("fluence", {1.0, 0.0}, {0.1, HUGE_VAL}), std::runtime_error);
  try {
    check_finite_tally("fluence", {std::nan("")}, {0.0});
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("fluence"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace scatterlab
