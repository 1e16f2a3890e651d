// The pieces of the lobe fits: the angular grid and its bin averages, the models' derivatives at
// the peak, model names, degenerate lobes, and the fits written into a simulation file.
#include <ceres/jet.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "../physics/lobe_fixtures.hpp"
#include "io/dimension_scales.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/fit/field_table.hpp"
#include "scatterlab/fit/lobe_fits_file.hpp"
#include "scatterlab/io/hdf5_file.hpp"
#include "scatterlab/io/simulation_file.hpp"

namespace scatterlab {
namespace {

namespace fs = std::filesystem;
using fit::FitStatus;
using fit::LobeModel;
using testing::angular_grid;
using testing::direction;
using testing::parameters;
using testing::synthesize;

constexpr double kPi = std::numbers::pi;

TEST(LobeGrid, SolidAnglesCoverTheSphereAndNodeWeightsSumToOne) {
  for (const bool folded : {false, true}) {
    const fit::LobeGrid grid = angular_grid(18, 36, 3, folded);
    double total = 0.0;
    for (std::size_t bin = 0; bin < grid.size(); ++bin) {
      total += grid.solid_angle(bin);
      double weights = 0.0;
      for (const fit::LobeNode& node : grid.nodes(bin)) {
        weights += node.weight;
        EXPECT_NEAR(node.direction.norm(), 1.0, 1e-14);
      }
      EXPECT_NEAR(weights, 1.0, 1e-14);
    }
    EXPECT_NEAR(total, folded ? 2.0 * kPi : 4.0 * kPi, 1e-12);
  }
}

TEST(LobeGrid, PlaneOfSymmetryIsTheFirstAndLastAndMiddlePhiBins) {
  const fit::LobeGrid grid = angular_grid(2, 8, 1);
  std::vector<std::size_t> in_plane;
  for (std::size_t f = 0; f < 8; ++f) {
    if (grid.in_symmetry_plane(f)) in_plane.push_back(f);
  }
  EXPECT_EQ(in_plane, (std::vector<std::size_t>{0, 3, 4, 7}));  // phi = 0, pi, pi, 2 pi
}

// The bin average of exp(lambda (cos t - 1)) about e_z over [t0, t1] x [f0, f1] is exactly
// (e^{lambda (cos t0 - 1)} - e^{lambda (cos t1 - 1)}) / (lambda (cos t0 - cos t1)).
TEST(LobeGrid, BinAveragesConvergeToTheExactIntegralWithTheOrder) {
  const auto sg = parameters(Eigen::Vector3d::UnitZ(), {50.0, 0.0});
  double previous_error = 1.0;
  for (const int order : {1, 2, 3, 5, 8}) {
    const fit::LobeGrid grid = angular_grid(18, 36, order);
    double worst = 0.0;
    for (std::size_t t = 0; t < 6; ++t) {  // the lobe lives within 60 degrees of e_z
      const double t0 = kPi * static_cast<double>(t) / 18.0, t1 = t0 + kPi / 18.0;
      const double exact =
          (std::exp(50.0 * (std::cos(t0) - 1.0)) - std::exp(50.0 * (std::cos(t1) - 1.0))) /
          (50.0 * (std::cos(t0) - std::cos(t1)));
      const double average = std::exp(fit::log_bin_average(LobeModel::sg, grid, t * 36, sg));
      worst = std::max(worst, std::abs(average / exact - 1.0));
    }
    EXPECT_LT(worst, previous_error) << order;
    previous_error = worst;
  }
  EXPECT_LT(previous_error, 1e-9);  // order 8
}

TEST(LobeGrid, RejectsBadEdgesAndOrders) {
  const std::vector<double> theta = {0.0, 1.0, 0.5}, phi = {0.0, 1.0};
  EXPECT_THROW(fit::LobeGrid(theta, phi, false), std::invalid_argument);
  EXPECT_THROW(fit::LobeGrid(std::vector<double>{0.0, 4.0}, phi, false), std::invalid_argument);
  EXPECT_THROW(fit::LobeGrid(std::vector<double>{0.0, 1.0}, phi, false, 9), std::invalid_argument);
}

// sqrt(1 - p.w) has an unbounded derivative at w = p; the models must stay finite there.
TEST(LobeModels, ResidualAndJacobianAreFiniteAtThePeak) {
  using Jet = ceres::Jet<double, 7>;
  for (const Eigen::Vector3d& w : {Eigen::Vector3d(0.0, 0.0, 1.0), direction(1.0, 0.3)}) {
    Jet axis[3], shape[4];
    for (int i = 0; i < 3; ++i) axis[i] = Jet(w[i], i);
    const double values[4] = {-1.0, 5.0, -2.0, 0.7};
    for (int i = 0; i < 4; ++i) shape[i] = Jet(values[i], 3 + i);
    for (const Jet& value : {fit::DoubleExponential::log_value(axis, shape, w),
                             fit::AnisotropicDoubleExponential::log_value(axis, shape, w)}) {
      EXPECT_NEAR(value.a, -1.0, 1e-12);  // a = log alpha + beta: log L at the peak
      EXPECT_TRUE(value.v.allFinite()) << value.v.transpose();
    }
  }
}

TEST(LobeModels, AnisotropicDoubleExponentialWithEtaZeroIsTheDoubleExponential) {
  const auto p = parameters(direction(0.8, 0.0), {-1.0, 5.0, -2.0, 0.0});
  for (const Eigen::Vector3d& w : {direction(0.1, 0.2), direction(2.0, 3.0), direction(3.1, 1.0)}) {
    EXPECT_NEAR(fit::log_model_value(LobeModel::adexp, p, w),
                fit::log_model_value(LobeModel::dexp, p, w), 1e-12);
  }
}

TEST(LobeModels, NamesParseAndUnknownOnesAreInputErrors) {
  EXPECT_EQ(fit::parse_lobe_models("sg,adexp"),
            (std::vector<LobeModel>{LobeModel::sg, LobeModel::adexp}));
  for (const char* bad : {"sg,glow", "", "sg,sg"}) {
    try {
      fit::parse_lobe_models(bad);
      ADD_FAILURE() << bad;
    } catch (const InputError& error) {
      EXPECT_EQ(error.field(), "models");
    }
  }
  EXPECT_EQ(fit::parameter_names(LobeModel::dexp),
            (std::vector<std::string>{"alpha", "beta", "gamma", "log_peak", "slope", "p_r", "p_phi",
                                      "p_z"}));
}

// Degenerate lobes are flagged with a message, never fitted into NaN.
TEST(LobeObservations, DegenerateLobesAreFlagged) {
  const fit::LobeGrid grid = angular_grid(18, 36, 3);
  std::vector<double> zero(grid.size(), 0.0), error(grid.size(), 0.0);
  auto status = [&](const std::vector<double>& mean, const std::vector<double>& stderr_of_mean) {
    const fit::LobeObservations o = fit::observe(grid, {mean, stderr_of_mean, {}}, {});
    EXPECT_FALSE(o.message.empty());
    return o.status;
  };
  EXPECT_EQ(status(zero, error), FitStatus::all_zero);
  std::vector<double> single = zero;
  single[100] = 3.0;
  EXPECT_EQ(status(single, error), FitStatus::too_few_directions);
  std::vector<double> nan = single;
  nan[7] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(status(nan, error), FitStatus::non_finite_input);
  std::vector<double> bad_error = error;
  bad_error[3] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(status(single, bad_error), FitStatus::non_finite_input);
  // Every direction seen once (relative stderr 1): too noisy to fit.
  const std::vector<double> ones(grid.size(), 1.0);
  EXPECT_EQ(status(ones, ones), FitStatus::too_few_directions);
}

// A small file: six spatial bins holding an SG, a double exponential, an anisotropic one, an
// all-zero bin, a bin with one non-zero direction and a bin with a NaN.
class LobeFitsFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    directory_ = fs::temp_directory_path() / ("scatterlab-fit-test-" + std::to_string(::getpid()) +
                                              "-" + std::to_string(counter++));
    fs::create_directories(directory_);
    path_ = directory_ / "lobes.h5";
    write_file();
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(directory_, ignored);
  }

  void write_file() { write_file(path_, 0.5, 0.9); }

  void write_file(const fs::path& path, double albedo, double g) {
    InfiniteMediumSpec spec;
    spec.medium.albedo = albedo;
    spec.medium.g = g;
    spec.grid.r = {0.0, 1.0, 2};
    spec.grid.z = {0.0, 3.0, 3};
    spec.grid.theta = {0.0, kPi, 9};
    spec.grid.phi = {0.0, 2.0 * kPi, 12};
    const fit::LobeGrid grid = angular_grid(9, 12, 3);
    TallyResult radiance{"radiance", {"r", "z", "theta", "phi"}, {2, 3, 9, 12}, "W", "L", {}, {}};
    TallyResult flux{"flux", {"r", "z", "component"}, {2, 3, 2}, "W", "E", {}, {}};
    const Eigen::Vector3d in_plane = direction(0.6, 0.0);
    const std::vector<testing::SyntheticLobe> lobes = {
        synthesize(LobeModel::sg, parameters(in_plane, {6.0, 0.0}), grid, 0.02, 1),
        synthesize(LobeModel::dexp,
                   parameters(in_plane, fit::double_exponential_shape(-3.0, 6.0, -2.0)), grid, 0.02,
                   2),
        synthesize(LobeModel::adexp,
                   parameters(in_plane, fit::double_exponential_shape(-3.0, 6.0, -2.0, -1.5)), grid,
                   0.02, 3)};
    for (std::size_t bin = 0; bin < 6; ++bin) {
      testing::SyntheticLobe lobe;
      if (bin < 3) {
        lobe = lobes[bin];
      } else {
        lobe.mean.assign(grid.size(), 0.0);
        lobe.stderr_of_mean.assign(grid.size(), 0.0);
        if (bin == 4) lobe.mean[20] = 1.0, lobe.stderr_of_mean[20] = 1.0;
      }
      radiance.mean.insert(radiance.mean.end(), lobe.mean.begin(), lobe.mean.end());
      radiance.stderr_of_mean.insert(radiance.stderr_of_mean.end(), lobe.stderr_of_mean.begin(),
                                     lobe.stderr_of_mean.end());
      flux.mean.insert(flux.mean.end(), {lobe.flux.x(), lobe.flux.z()});
      flux.stderr_of_mean.insert(flux.stderr_of_mean.end(), {0.0, 0.0});
    }
    Provenance provenance;
    provenance.version = provenance.command = "test";
    provenance.created = "2024-01-01T00:00:00Z";
    write_simulation_file(path, spec, {radiance, flux}, provenance);
    // The NaN goes in afterwards: the writer refuses one (check_finite_tally), but fit must cope
    // with a file from elsewhere that holds one.
    hdf5::File file = hdf5::File::open_read_write(path);
    hdf5::Group tally = file.root().open_group("tallies/radiance");
    hdf5::Array mean = tally.read_dataset("mean");
    std::vector<std::pair<std::string, std::string>> attributes;
    {
      const hdf5::Dataset written = tally.open_dataset("mean");
      for (const std::string& name : written.attribute_names()) {
        if (is_dimension_scale_attribute(name)) continue;  // references, not text
        attributes.emplace_back(name, written.read_string_attribute(name));
      }
    }
    mean.values[5 * grid.size() + 5] = std::numeric_limits<double>::quiet_NaN();
    tally.remove_member("mean");
    hdf5::Dataset with_nan = tally.write_dataset("mean", mean.values, mean.shape);
    for (const auto& [name, value] : attributes) with_nan.write_string_attribute(name, value);
    file.close();
  }

  fit::LobeFitRun fit_file(int threads) {
    const fit::RadianceLobes lobes = fit::read_radiance_lobes(path_);
    const fit::LobeGrid grid(lobes.theta_edges, lobes.phi_edges, lobes.phi_folded);
    fit::LobeFitRun run = fit::fit_lobes(
        lobes, grid, {fit::kAllLobeModels.begin(), fit::kAllLobeModels.end()}, {}, threads);
    fit::write_fits(lobes, grid, run, {});
    return run;
  }

  fs::path directory_, path_;
};

TEST_F(LobeFitsFileTest, FitsAreWrittenWithNamesStatusAndNoNaN) {
  const fit::LobeFitRun run = fit_file(2);
  const hdf5::File file = hdf5::File::open_read_only(path_);
  for (const LobeModel model : fit::kAllLobeModels) {
    const std::string name = "fits/" + fit::to_string(model);
    const hdf5::Dataset params = file.root().open_dataset(name + "/params");
    const std::vector<std::string> names = fit::parameter_names(model);
    EXPECT_EQ(params.shape(), (std::vector<std::size_t>{2, 3, names.size()}));
    EXPECT_EQ(params.read_string_attribute("names").find(names[0]), 0u);
    for (const char* dataset : {"params", "error", "error_plane", "noise", "chi2_dof", "status"}) {
      for (const double value : file.root().read_dataset(name + "/" + dataset).values) {
        EXPECT_TRUE(std::isfinite(value)) << name << "/" << dataset;
      }
    }
    const std::vector<double> status = file.root().read_dataset(name + "/status").values;
    EXPECT_EQ(status[3], static_cast<double>(FitStatus::all_zero)) << name;
    EXPECT_EQ(status[4], static_cast<double>(FitStatus::too_few_directions)) << name;
    EXPECT_EQ(status[5], static_cast<double>(FitStatus::non_finite_input)) << name;
    const std::vector<double> error = file.root().read_dataset(name + "/error").values;
    for (std::size_t bin = 0; bin < 3; ++bin) {
      const auto expected =
          model == LobeModel::dexp_paper ? FitStatus::estimate : FitStatus::converged;
      EXPECT_EQ(status[bin], static_cast<double>(expected)) << name << " " << bin;
      EXPECT_GE(error[bin], 0.0);
    }
    for (std::size_t bin = 3; bin < 6; ++bin) EXPECT_EQ(error[bin], -1.0);
    EXPECT_NE(file.root()
                  .open_dataset(name + "/status")
                  .read_string_attribute("legend")
                  .find("11 too_few_directions"),
              std::string::npos);
  }
  // Each model fits its own lobe to the noise (2 %: an L1 error of about 1.6 %).
  const std::vector<double> sg = file.root().read_dataset("fits/sg/error").values;
  const std::vector<double> dexp = file.root().read_dataset("fits/dexp/error").values;
  const std::vector<double> adexp = file.root().read_dataset("fits/adexp/error").values;
  EXPECT_LT(sg[0], 0.025);
  EXPECT_LT(dexp[1], 0.025);
  EXPECT_LT(adexp[2], 0.025);
  EXPECT_LT(adexp[2], 0.5 * dexp[2]);  // the flattening costs dexp
  const fit::LobeFitSummary summary = fit::summarize(run);
  EXPECT_EQ(summary.models[0].fitted, 3u);
  EXPECT_EQ(summary.models[0].skipped, 3u);
  // Each model that contains another started from its solution: never a larger chi-square.
  EXPECT_EQ(summary.supersets.size(), 5u);  // sg_free, dexp, adexp, adexp_ridge, adexp2_ridge
  for (const fit::SupersetCheck& check : summary.supersets) {
    EXPECT_EQ(check.bins, 3u) << fit::to_string(check.superset);
    EXPECT_EQ(check.worse_chi2, 0u) << fit::to_string(check.superset);
  }
}

TEST_F(LobeFitsFileTest, ResultsDoNotDependOnThreadsAndReRunsReplaceTheFits) {
  const fit::LobeFitRun one = fit_file(1);
  const fit::LobeFitRun two = fit_file(2);  // also replaces /fits/<model> in place
  for (std::size_t m = 0; m < one.models.size(); ++m) {
    for (std::size_t bin = 0; bin < one.models[m].fits.size(); ++bin) {
      const auto& a = one.models[m].fits[bin];
      const auto& b = two.models[m].fits[bin];
      EXPECT_EQ(a.status, b.status);
      EXPECT_EQ(a.parameters.shape, b.parameters.shape);
      EXPECT_EQ(a.parameters.axis, b.parameters.axis);
      EXPECT_EQ(a.parameters.second_shape, b.parameters.second_shape);
    }
  }
  const hdf5::File file = hdf5::File::open_read_only(path_);
  EXPECT_EQ(file.root().open_group("fits").member_names(),
            (std::vector<std::string>{"sg", "sg_free", "dexp_paper", "dexp", "adexp", "asg",
                                      "adexp_ridge", "adexp2_ridge"}));
  // Nothing left beside the file.
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(directory_)) ++entries;
  EXPECT_EQ(entries, 1u);
}

TEST_F(LobeFitsFileTest, CsvHasOneRowPerSpatialBin) {
  const fit::RadianceLobes lobes = fit::read_radiance_lobes(path_);
  const fit::LobeGrid grid(lobes.theta_edges, lobes.phi_edges, lobes.phi_folded);
  const fit::LobeFitRun run = fit::fit_lobes(lobes, grid, {LobeModel::sg, LobeModel::dexp}, {}, 1);
  fit::write_fits_csv(directory_ / "fits.csv", lobes, run);
  std::ifstream csv(directory_ / "fits.csv");
  std::string header, line;
  std::getline(csv, header);
  EXPECT_EQ(header.find("r_index,z_index,r,z,sg_status,sg_error,sg_error_plane,sg_noise,"
                        "sg_chi2_dof,sg_lambda"),
            0u);
  std::size_t rows = 0;
  while (std::getline(csv, line)) {
    ++rows;
    EXPECT_EQ(line.find("nan"), std::string::npos) << line;
  }
  EXPECT_EQ(rows, 6u);
}

// A sweep directory: one table row per file and spatial bin, with the file's albedo and g, and
// each file's own fits; a file without the radiance tally stops the run before any is written.
TEST_F(LobeFitsFileTest, ASweepDirectoryGivesOneTableAgainstAlbedoAndG) {
  const fs::path sweep = directory_ / "sweep";
  fs::create_directories(sweep);
  write_file(sweep / "albedo=0.3_g=0.5.h5", 0.3, 0.5);
  write_file(sweep / "albedo=0.9_g=0.0.h5", 0.9, 0.0);
  const fit::FieldFit field =
      fit::fit_field(sweep, directory_ / "table.csv", {LobeModel::sg, LobeModel::dexp}, {}, 3, 1);
  ASSERT_EQ(field.runs.size(), 2u);
  std::ifstream csv(directory_ / "table.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line.find("file,albedo,g,r_index,z_index,r,z,sg_status"), 0u) << line;
  std::vector<std::string> rows;
  while (std::getline(csv, line)) rows.push_back(line);
  ASSERT_EQ(rows.size(), 12u);  // 2 files x 6 bins, in name order
  EXPECT_EQ(rows[0].find("albedo=0.3_g=0.5.h5,0.3,0.5,0,0,"), 0u) << rows[0];
  EXPECT_EQ(rows[6].find("albedo=0.9_g=0.0.h5,0.9,0,0,0,"), 0u) << rows[6];
  for (const fs::path& file : fit::sweep_files(sweep)) {
    EXPECT_TRUE(hdf5::File::open_read_only(file).root().has_member("fits/dexp")) << file;
  }

  const fs::path bad = directory_ / "bad-sweep";
  fs::create_directories(bad);
  write_file(bad / "a.h5", 0.5, 0.9);
  write_simulation_file(bad / "b.h5", InfiniteMediumSpec{}, {}, Provenance{});
  EXPECT_THROW(fit::fit_field(bad, directory_ / "bad.csv", {LobeModel::sg}, {}, 3, 1), InputError);
  EXPECT_FALSE(hdf5::File::open_read_only(bad / "a.h5").root().has_member("fits"));
  EXPECT_FALSE(fs::exists(directory_ / "bad.csv"));
}

TEST_F(LobeFitsFileTest, FilesWithoutRadianceAreInputErrors) {
  const fs::path other = directory_ / "no-radiance.h5";
  InfiniteMediumSpec spec;
  write_simulation_file(other, spec, {}, Provenance{});
  try {
    fit::read_radiance_lobes(other);
    ADD_FAILURE();
  } catch (const InputError& error) {
    EXPECT_EQ(error.field(), "FILE");
    EXPECT_NE(std::string(error.what()).find("radiance"), std::string::npos);
  }
  EXPECT_THROW(fit::read_radiance_lobes(directory_ / "missing.h5"), InputError);
}

}  // namespace
}  // namespace scatterlab
