// Sweep files: lists of values at scalar keys expand to every combination, each a valid scene.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/scene.hpp"

namespace scatterlab {
namespace {

std::vector<std::string> labels(const std::vector<SweepPoint>& points) {
  std::vector<std::string> result;
  for (const SweepPoint& point : points) result.push_back(point.label);
  return result;
}

TEST(Sweep, EveryCombinationInFileOrderLastFastest) {
  const auto points = parse_sweep(
      "[medium]\nalbedo = [0.5, 0.9]\ng = [0, 0.9, -0.3]\n[run]\nphotons = 1e4\n", "sweep.toml");
  ASSERT_EQ(points.size(), 6u);
  EXPECT_EQ(labels(points),
            (std::vector<std::string>{"albedo=0.5_g=0", "albedo=0.5_g=0.9", "albedo=0.5_g=-0.3",
                                      "albedo=0.9_g=0", "albedo=0.9_g=0.9", "albedo=0.9_g=-0.3"}));
  EXPECT_EQ(points[4].scene.spec.medium.albedo, 0.9);
  EXPECT_EQ(points[4].scene.spec.medium.g, 0.9);
  EXPECT_EQ(points[5].scene.spec.medium.g, -0.3);
  for (const SweepPoint& point : points) EXPECT_EQ(point.scene.spec.run.photons, 10000u);
}

TEST(Sweep, FileWithoutListsIsOnePointWithoutLabel) {
  const auto points = parse_sweep("[medium]\nalbedo = 0.7\n", "one.toml");
  ASSERT_EQ(points.size(), 1u);
  EXPECT_EQ(points[0].label, "");
  EXPECT_EQ(points[0].scene.spec.medium.albedo, 0.7);
}

TEST(Sweep, KeysSharingTheirLastPartAreLabelledInFull) {
  const auto points = parse_sweep(
      "[source]\ntype = \"point\"\n[grid]\nr = { max = [1, 2] }\nrho = { max = 5 }\n"
      "[tallies]\nestimator = [\"collision\", \"track_length\"]\n",
      "s.toml");
  EXPECT_EQ(labels(points), (std::vector<std::string>{
                                "max=1_estimator=collision", "max=1_estimator=track_length",
                                "max=2_estimator=collision", "max=2_estimator=track_length"}));
  const auto both = parse_sweep("[grid]\nr = { max = [1, 2] }\nz = { max = [3] }\n", "s.toml");
  EXPECT_EQ(labels(both),
            (std::vector<std::string>{"grid.r.max=1_grid.z.max=3", "grid.r.max=2_grid.z.max=3"}));
}

TEST(Sweep, EveryPointIsValidatedAndBadListsAreNamed) {
  auto field_of = [](const std::string& text) {
    try {
      parse_sweep(text, "bad.toml");
    } catch (const InputError& error) {
      return error.field();
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(field_of("[medium]\nalbedo = [0.5, 1.5]\n"), "medium.albedo");
  EXPECT_EQ(field_of("[medium]\nalbedo = []\n"), "medium.albedo");
  EXPECT_EQ(field_of("[medium]\ng = [[0.1], [0.2]]\n"), "medium.g");
  EXPECT_EQ(field_of("[medium]\nalbdo = [0.5]\n"), "medium.albdo");
  // A single scene file still takes one value per key.
  EXPECT_THROW(parse_scene("[medium]\nalbedo = [0.5, 0.9]\n", "one.toml"), InputError);
}

TEST(Sweep, ShippedSweepHasNineRuns) {
  const auto points =
      load_sweep(std::filesystem::path(SCATTERLAB_SOURCE_DIR) / "data/scenes/sweep-albedo-g.toml");
  ASSERT_EQ(points.size(), 9u);
  EXPECT_EQ(points.back().label, "albedo=0.99_g=0.9");
}

}  // namespace
}  // namespace scatterlab
