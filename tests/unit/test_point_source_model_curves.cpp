// The point source's model curves as simulate writes them under /models: the three models'
// shell averages on the run's shells, in the run's length unit with the tally's units, and, where
// the models do not hold, a note per model saying why.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "scatterlab/models/point_source_diffusion.hpp"
#include "scatterlab/models/point_source_exact.hpp"
#include "scatterlab/models/point_source_grosjean.hpp"
#include "validate/point_source_models.hpp"

namespace scatterlab {
namespace {

InfiniteMediumSpec point_source(double albedo, double g) {
  InfiniteMediumSpec spec;
  spec.set_source(SourceKind::point);
  spec.medium.albedo = albedo;
  spec.medium.g = g;
  spec.grid.rho = {0.0, 4.0, 8};
  return spec;
}

// The fluence_spherical tally of such a run, as transport hands it over (values do not matter).
std::vector<TallyResult> tallies_of(const InfiniteMediumSpec& spec, const std::string& units) {
  const std::size_t shells = static_cast<std::size_t>(spec.grid.rho.bins);
  return {{"fluence_spherical",
           {"rho"},
           {shells},
           units,
           "",
           std::vector<double>(shells, 1.0),
           std::vector<double>(shells, 0.1)}};
}

TEST(PointSourceModelCurves, TheThreeModelsOnTheRunsShells) {
  const InfiniteMediumSpec spec = point_source(0.7, 0.0);
  const auto models = point_source_model_curves(spec, tallies_of(spec, "W mfp^-2 per W incident"));
  ASSERT_EQ(models.size(), 3u);
  for (const ModelResult& m : models) {
    EXPECT_EQ(m.name, "fluence_spherical");
    EXPECT_EQ(m.units, "W mfp^-2 per W incident");
    EXPECT_EQ(m.dims, std::vector<std::string>{"rho"});
    ASSERT_EQ(m.values.size(), 8u) << m.model;
  }
  EXPECT_EQ(models[0].model, "exact");
  EXPECT_EQ(models[1].model, "diffusion");
  EXPECT_EQ(models[2].model, "grosjean");
  // Shell [1.5, 2) mfp.
  EXPECT_EQ(models[0].values[3], point_source_fluence_shell_average(0.7, 1.5, 2.0));
  EXPECT_EQ(models[1].values[3], diffusion_point_source_shell_average(0.7, 1.5, 2.0));
  EXPECT_EQ(models[2].values[3], grosjean_point_source_shell_average(0.7, 1.5, 2.0));
}

TEST(PointSourceModelCurves, InTheRunsLengthUnit) {
  // sigma_t = 2 / mm: the shell [0.5, 1) mm is [1, 2) mfp, and 1 mfp^-2 is 4 mm^-2.
  InfiniteMediumSpec spec = point_source(0.9, 0.0);
  spec.medium.sigma_t = 2.0;
  spec.medium.length_unit = "mm";
  spec.grid.rho = {0.0, 2.0, 4};
  const auto models = point_source_model_curves(spec, tallies_of(spec, "W mm^-2 per W incident"));
  ASSERT_EQ(models.size(), 3u);
  EXPECT_EQ(models[0].units, "W mm^-2 per W incident");
  EXPECT_DOUBLE_EQ(models[0].values[1], 4.0 * point_source_fluence_shell_average(0.9, 1.0, 2.0));
}

TEST(PointSourceModelCurves, ANoteWhereTheModelsDoNotHold) {
  for (const auto& [spec, field] :
       {std::pair{point_source(0.7, 0.5), std::string("g")},
        std::pair{point_source(0.7, 0.0), std::string("escape radius")}}) {
    InfiniteMediumSpec run = spec;
    if (field == "escape radius") run.run.escape_radius = 3.0;
    const auto models = point_source_model_curves(run, tallies_of(run, "W mfp^-2 per W incident"));
    ASSERT_EQ(models.size(), 3u) << field;
    for (const ModelResult& m : models) {
      EXPECT_TRUE(m.values.empty()) << m.model;
      EXPECT_NE(m.description.find(field), std::string::npos) << m.description;
    }
  }
}

TEST(PointSourceModelCurves, NoneForTheBeam) {
  InfiniteMediumSpec beam;
  beam.medium.g = 0.0;
  EXPECT_TRUE(point_source_model_curves(beam, tallies_of(point_source(0.5, 0.0), "")).empty());
}

}  // namespace
}  // namespace scatterlab
