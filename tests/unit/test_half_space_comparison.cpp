// The half-space comparison and its report, with the models alone and with a Monte Carlo curve
// given as input for the multiply-scattered part (here the better dipole itself with a 1% error
// bar, so its error must be 0, and the models of other parts must not be scored against it).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "scatterlab/core/error.hpp"
#include "scatterlab/models/dipole.hpp"
#include "scatterlab/validate/half_space_comparison.hpp"
#include "scatterlab/validate/validation_report.hpp"

namespace scatterlab {
namespace {

TEST(HalfSpaceComparison, ScoresModelsAgainstGivenMonteCarloCurves) {
  const HalfSpaceMedium medium = HalfSpaceMedium::from_albedo(0.9, 0.0, 1.33);
  std::vector<double> r_edges, z_edges{0.0, 0.5, 1.0, 2.0};
  for (int i = 0; i <= 10; ++i) r_edges.push_back(0.2 * i);
  const double transmittance = 0.98;
  MonteCarloCurve mc;
  mc.mean = dipole_reflectance_annulus_average(better_dipole(medium), r_edges);
  for (double& v : mc.mean) v *= transmittance;
  for (double v : mc.mean) mc.stderr_of_mean.push_back(0.01 * v);
  const HalfSpaceComparison c = compare_half_space(medium, transmittance, r_edges, z_edges,
                                                   {{ModelPart::multiple, mc}}, {}, 1.0);
  // single scatter; four diffusion models; the same plus single scatter; the Grosjean beam's
  // multiply-scattered part and its total.
  ASSERT_EQ(c.reflectance.size(), 11u);
  EXPECT_EQ(c.reflectance[2].model, "better_dipole");
  EXPECT_EQ(c.reflectance[2].part, ModelPart::multiple);
  EXPECT_NEAR(c.reflectance[2].near_error, 0.0, 1e-14);
  EXPECT_NEAR(c.reflectance[2].far_error, 0.0, 1e-14);
  EXPECT_GT(c.reflectance[1].near_error, 0.01);  // the classical dipole differs
  EXPECT_EQ(c.reflectance[4].model, "photon_beam_diffusion");
  EXPECT_GT(c.reflectance[4].near_error, 0.01);  // kappa takes light near the beam
  EXPECT_EQ(c.reflectance[6].model, "better_dipole+single_scatter");
  EXPECT_EQ(c.reflectance[6].part, ModelPart::all);
  EXPECT_TRUE(std::isnan(c.reflectance[6].near_error));  // no total given to compare with
  EXPECT_NEAR(c.reflectance[6].total, c.reflectance[2].total + c.reflectance[0].total, 1e-15);
  EXPECT_TRUE(std::isnan(c.reflectance[0].near_error));  // nor a once-scattered part
  EXPECT_TRUE(std::isnan(c.fluence[0].near_error));  // no Monte Carlo fluence given
  EXPECT_EQ(c.fluence[0].values.size(), 30u);

  const auto dir = std::filesystem::temp_directory_path() / "scatterlab_test_half_space_report";
  const auto files = write_half_space_report(c, dir, "searchlight");
  EXPECT_EQ(files.size(), 12u);  // 2 CSV, 4 pencil plots for two parts, 2 fluence plots
  for (const auto& f : files) EXPECT_GT(std::filesystem::file_size(f), 100u) << f;
  std::filesystem::remove_all(dir);

  MonteCarloCurve wrong{{1.0}, {0.1}};
  EXPECT_THROW(compare_half_space(medium, 1.0, r_edges, z_edges, {{ModelPart::all, wrong}}),
               InputError);
}

}  // namespace
}  // namespace scatterlab
