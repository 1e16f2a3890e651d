// Sweep files: lists of values at scalar keys expand to every combination, each a valid scene.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <variant>
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
  EXPECT_EQ(std::get<InfiniteMediumSpec>(points[4].scene.spec).medium.albedo, 0.9);
  EXPECT_EQ(std::get<InfiniteMediumSpec>(points[4].scene.spec).medium.g, 0.9);
  EXPECT_EQ(std::get<InfiniteMediumSpec>(points[5].scene.spec).medium.g, -0.3);
  for (const SweepPoint& point : points)
    EXPECT_EQ(std::get<InfiniteMediumSpec>(point.scene.spec).run.photons, 10000u);
}

TEST(Sweep, FileWithoutListsIsOnePointWithoutLabel) {
  const auto points = parse_sweep("[medium]\nalbedo = 0.7\n", "one.toml");
  ASSERT_EQ(points.size(), 1u);
  EXPECT_EQ(points[0].label, "");
  EXPECT_EQ(std::get<InfiniteMediumSpec>(points[0].scene.spec).medium.albedo, 0.7);
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

// Sweeps are the reader's, so every geometry has them: a slab's layer (the keys of [[layers]]
// named by their layer), a sphere's radius, a half-space's index and incidence.
TEST(Sweep, EveryGeometrySweepsItsOwnKeys) {
  const auto slab = parse_sweep(
      "[geometry]\ntype = \"slab\"\n[[layers]]\nmu_a = 1\nmu_s = 10\ng = 0.9\nn = 1.4\n"
      "thickness = 0.1\n[[layers]]\nmu_a = 0.5\nmu_s = 20\ng = 0.8\nn = 1.4\n"
      "thickness = [0.5, 1, inf]\n",
      "slab.toml");
  EXPECT_EQ(labels(slab),
            (std::vector<std::string>{"thickness=0.5", "thickness=1", "thickness=inf"}));
  const auto& deep = std::get<LayeredSlabSpec>(slab[1].scene.spec);
  ASSERT_EQ(deep.layers.size(), 2u);
  EXPECT_EQ(deep.layers[0].thickness, 0.1);
  EXPECT_EQ(deep.layers[1].thickness, 1.0);
  EXPECT_EQ(slab[1].scene.geometry(), "slab");
  // Two layers' thicknesses: the label names each by its layer.
  const auto both = parse_sweep(
      "[geometry]\ntype = \"slab\"\n[[layers]]\nmu_a = 1\nmu_s = 10\ng = 0.9\nn = 1.4\n"
      "thickness = [0.1, 0.2]\n[[layers]]\nmu_a = 0.5\nmu_s = 20\ng = 0.8\nn = 1.4\n"
      "thickness = [1, 2]\n",
      "slab.toml");
  EXPECT_EQ(labels(both).front(), "layers[1].thickness=0.1_layers[2].thickness=1");

  const auto sphere =
      parse_sweep("[geometry]\ntype = \"sphere\"\nradius = [0.5, 1, 2]\n", "sphere.toml");
  ASSERT_EQ(sphere.size(), 3u);
  EXPECT_EQ(std::get<LitObjectSpec>(sphere[2].scene.spec).radius, 2.0);
  EXPECT_EQ(sphere[2].label, "radius=2");

  const auto half = parse_sweep("[geometry]\neta = [1, 1.3]\n[source]\nincidence_deg = [0, 60]\n",
                                "half.toml", Validation::on_read, "half_space");
  ASSERT_EQ(half.size(), 4u);
  EXPECT_EQ(std::get<HalfSpaceSpec>(half[3].scene.spec).incidence_deg, 60.0);
  EXPECT_EQ(std::get<HalfSpaceSpec>(half[3].scene.spec).eta, 1.3);
}

// A key whose value is a vector is one value as a list of numbers, and is swept by a list of
// vectors; a mesh's keys sweep too, its [mesh] table written out for each point.
TEST(Sweep, VectorsAndMeshKeys) {
  const std::string beam =
      "[geometry]\ntype = \"sphere\"\n[source]\ntype = \"beam\"\ndirection = [0, 0, 1]\n";
  const auto one = parse_sweep(beam + "origin = [0, 0, -3]\n", "beam.toml");
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].label, "");
  const auto two = parse_sweep(beam + "origin = [[0, 0, -3], [0.5, 0, -3]]\n", "beam.toml");
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[1].label, "origin=0.5,0,-3");
  EXPECT_EQ(std::get<LitObjectSpec>(two[1].scene.spec).beam_origin[0], 0.5);
  EXPECT_THROW(parse_sweep(beam + "origin = [[0, 0, -3], 1]\n", "beam.toml"), InputError);

  const auto mesh = parse_sweep(
      "[geometry]\ntype = \"mesh\"\n[mesh]\nshape = \"sphere\"\nrings = [8, 16]\n", "mesh.toml");
  ASSERT_EQ(mesh.size(), 2u);
  EXPECT_EQ(mesh[1].scene.geometry(), "mesh");
  ASSERT_TRUE(mesh[1].scene.mesh_text.has_value());
  EXPECT_NE(mesh[1].scene.mesh_text->find("rings = 16"), std::string::npos)
      << *mesh[1].scene.mesh_text;
}

TEST(Sweep, ShippedSweepHasNineRuns) {
  const auto points =
      load_sweep(std::filesystem::path(SCATTERLAB_SOURCE_DIR) / "data/scenes/sweep-albedo-g.toml");
  ASSERT_EQ(points.size(), 9u);
  EXPECT_EQ(points.back().label, "albedo=0.99_g=0.9");
}

}  // namespace
}  // namespace scatterlab
