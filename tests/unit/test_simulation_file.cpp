// The HDF5 output layer: the simulation file round trip (the public layout of simulation_file.hpp),
// atomic output, `scatterlab info`, and the errors of the HDF5 wrapper.

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/dimension_scales.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/io/atomic_output.hpp"
#include "scatterlab/io/hdf5_file.hpp"
#include "scatterlab/io/simulation_file.hpp"
#include "scratch_directory.hpp"

namespace scatterlab {
namespace {

namespace fs = std::filesystem;

// A fresh directory per test (scratch_directory.hpp).
class SimulationFileTest : public test_support::ScratchDirectoryTest {
 protected:
  std::vector<std::string> directory_entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(directory_)) {
      names.push_back(entry.path().filename().string());
    }
    return names;
  }
};

InfiniteMediumSpec small_spec() {
  InfiniteMediumSpec spec;
  spec.medium = Medium{0.8, 2.0, 0.9, "mm"};
  spec.source = SourceKind::point;
  spec.grid.r = {0.0, 1.5, 3};
  spec.grid.z = {-1.0, 3.0, 4};
  spec.grid.theta = {0.0, std::numbers::pi, 2};
  spec.grid.phi = {0.0, std::numbers::pi, 5};
  spec.grid.fold_phi = true;
  spec.grid.rho = {0.0, 10.0, 6};
  spec.tallies.fluence_spherical = true;
  spec.tallies.split_by_order = true;
  spec.tallies.estimator = Estimator::track_length;
  spec.run.photons = 1000;
  spec.run.batches = 10;
  spec.run.seed = std::numeric_limits<std::uint64_t>::max();  // every 64-bit seed survives
  spec.run.threads = 3;
  spec.run.escape_radius = 50.0;
  return spec;
}

TallyResult array_tally(std::string name, std::vector<std::string> dims,
                        std::vector<std::size_t> shape) {
  TallyResult tally;
  tally.name = std::move(name);
  tally.dims = std::move(dims);
  tally.shape = std::move(shape);
  tally.units = "W mfp^-2 per W incident";
  tally.description = tally.name + " by the track-length estimator";
  std::size_t values = 1;
  for (const std::size_t extent : tally.shape) values *= extent;
  for (std::size_t i = 0; i < values; ++i) {
    const double x = static_cast<double>(i);
    tally.mean.push_back(i % 7 == 0 ? 0.0 : 0.5 + std::sin(x));  // some empty bins
    tally.stderr_of_mean.push_back(0.01 * (1.0 + std::cos(x) * std::cos(x)));
  }
  return tally;
}

TallyResult scalar_tally(std::string name, double value, double error) {
  TallyResult tally;
  tally.name = std::move(name);
  tally.units = "per W incident";
  tally.description = "energy absorbed inside the grid";
  tally.mean = {value};
  tally.stderr_of_mean = {error};
  return tally;
}

std::vector<TallyResult> small_tallies() {
  return {array_tally("radiance", {"r", "z", "theta", "phi"}, {3, 4, 2, 5}),
          array_tally("fluence", {"r", "z"}, {3, 4}), scalar_tally("absorbed", 0.75, 0.002)};
}

Provenance small_provenance() {
  return {"0.1.0",
          "scatterlab simulate --albedo 0.8 --out run.h5",
          "2024-05-01T12:34:56Z",
          12.5,
          1000,
          123456789012,
          std::nullopt,  // every batch ran
          1};
}

TEST_F(SimulationFileTest, RoundTripKeepsLayoutValuesAndAttributes) {
  const fs::path path = directory_ / "run.h5";
  const InfiniteMediumSpec spec = small_spec();
  const std::vector<TallyResult> tallies = small_tallies();
  write_simulation_file(path, spec, tallies, small_provenance());

  const hdf5::File file = hdf5::File::open_read_only(path);
  const hdf5::Group& root = file.root();
  EXPECT_EQ(root.member_names(),
            (std::vector<std::string>{"parameters", "grid", "tallies", "figures_of_merit"}));
  EXPECT_EQ(root.attribute_type("format"), hdf5::AttributeType::string);
  EXPECT_EQ(root.read_string_attribute("format"), "scatterlab");
  EXPECT_EQ(root.read_int64_attribute("format_version"), 1);
  EXPECT_EQ(root.read_string_attribute("scatterlab_version"), "0.1.0");
  EXPECT_EQ(root.read_string_attribute("command"), "scatterlab simulate --albedo 0.8 --out run.h5");
  EXPECT_EQ(root.read_string_attribute("created"), "2024-05-01T12:34:56Z");
  EXPECT_EQ(root.read_double_attribute("wall_seconds"), 12.5);
  EXPECT_EQ(root.read_int64_attribute("photons_run"), 1000);
  EXPECT_EQ(root.read_int64_attribute("scattering_events"), 123456789012);
  // A run in one process: its session is the whole run.
  EXPECT_EQ(root.read_double_attribute("session_wall_seconds"), 12.5);
  EXPECT_EQ(root.read_int64_attribute("session_photons_run"), 1000);
  // 1 / (R^2 T) with R = 0.002 / 0.75 and T = wall_seconds.
  const hdf5::Dataset merit = root.open_dataset("figures_of_merit/absorbed");
  EXPECT_DOUBLE_EQ(merit.read().values.at(0), 1.0 / ((0.002 / 0.75) * (0.002 / 0.75) * 12.5));
  EXPECT_EQ(merit.read_string_attribute("units"), "1/s");

  const hdf5::Group parameters = root.open_group("parameters");
  EXPECT_EQ(parameters.read_string_attribute("source"), "point");
  EXPECT_EQ(parameters.read_double_attribute("albedo"), 0.8);
  EXPECT_EQ(parameters.read_double_attribute("g"), 0.9);
  EXPECT_EQ(parameters.read_double_attribute("sigma_t"), 2.0);
  EXPECT_EQ(parameters.read_double_attribute("sigma_a"), spec.medium.sigma_a());
  EXPECT_EQ(parameters.read_double_attribute("sigma_s"), spec.medium.sigma_s());
  EXPECT_EQ(parameters.read_string_attribute("length_unit"), "mm");
  EXPECT_EQ(parameters.read_string_attribute("phase"), "henyey-greenstein");
  EXPECT_EQ(parameters.read_int64_attribute("photons"), 1000);
  EXPECT_EQ(parameters.read_int64_attribute("batches"), 10);
  EXPECT_EQ(parameters.attribute_type("seed"), hdf5::AttributeType::unsigned_integer);
  EXPECT_EQ(parameters.read_uint64_attribute("seed"), std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(parameters.read_string_attribute("estimator"), "track_length");
  EXPECT_EQ(parameters.read_double_attribute("escape_radius"), 50.0);
  EXPECT_EQ(parameters.read_int64_attribute("split_by_order"), 1);
  EXPECT_EQ(parameters.read_int64_attribute("threads"), 3);

  const hdf5::Group grid = root.open_group("grid");
  EXPECT_EQ(grid.read_int64_attribute("phi_folded"), 1);
  EXPECT_EQ(grid.member_names(), (std::vector<std::string>{"r", "z", "theta", "phi", "rho"}));
  const std::pair<const char*, const UniformAxis*> axes[] = {{"r", &spec.grid.r},
                                                             {"z", &spec.grid.z},
                                                             {"theta", &spec.grid.theta},
                                                             {"phi", &spec.grid.phi},
                                                             {"rho", &spec.grid.rho}};
  for (const auto& [name, axis] : axes) {
    const hdf5::Array edges = grid.read_dataset(name);
    EXPECT_EQ(edges.shape, std::vector<std::size_t>{axis->edges().size()}) << name;
    EXPECT_EQ(edges.values, axis->edges()) << name;
    const bool angle = std::string(name) == "theta" || std::string(name) == "phi";
    // Lengths are in the medium's unit (here mm: the spec's grid is read in it).
    EXPECT_EQ(grid.open_dataset(name).read_string_attribute("units"), angle ? "rad" : "mm");
  }

  const hdf5::Group group = root.open_group("tallies");
  EXPECT_EQ(group.member_names(),
            (std::vector<std::string>{"radiance", "fluence", "absorbed"}));  // as given
  for (const TallyResult& tally : tallies) {
    const hdf5::Group node = group.open_group(tally.name);
    EXPECT_EQ(node.read_string_attribute("units"), tally.units);
    EXPECT_EQ(node.read_string_attribute("description"), tally.description);
    const hdf5::Array mean = node.read_dataset("mean");
    const hdf5::Array error = node.read_dataset("stderr");
    EXPECT_EQ(mean.shape, tally.shape) << tally.name;
    EXPECT_EQ(error.shape, tally.shape) << tally.name;
    EXPECT_EQ(mean.values, tally.mean) << tally.name;
    EXPECT_EQ(error.values, tally.stderr_of_mean) << tally.name;
    EXPECT_EQ(node.open_dataset("mean").read_string_attribute("units"), tally.units);
  }
  EXPECT_EQ(group.open_group("radiance").read_string_attribute("dims"), "r,z,theta,phi");
  EXPECT_EQ(group.open_group("fluence").read_string_attribute("dims"), "r,z");
  EXPECT_EQ(group.open_group("absorbed").read_string_attribute("dims"), "");
  EXPECT_TRUE(group.open_dataset("absorbed/mean").shape().empty());  // rank-0 scalar
}

// Every tally's dimensions have HDF5 dimension scales beside its data (dimension_scales.hpp):
// the grid's bin centres in its units, or the bin index where the grid has no such axis. The
// attachments themselves are read back by xarray in tests/python.
TEST_F(SimulationFileTest, TallyDimensionsHaveScalesOfBinCentres) {
  const fs::path path = directory_ / "run.h5";
  const InfiniteMediumSpec spec = small_spec();
  std::vector<TallyResult> tallies = small_tallies();
  tallies.push_back(array_tally("flux", {"r", "z", "component"}, {3, 4, 2}));
  write_simulation_file(path, spec, tallies, small_provenance());

  const hdf5::File file = hdf5::File::open_read_only(path);
  const hdf5::Group fluence = file.root().open_group("tallies/fluence");
  EXPECT_EQ(fluence.member_names(), (std::vector<std::string>{"mean", "stderr", "r", "z"}));
  EXPECT_FALSE(fluence.open_dataset("mean").is_dimension_scale());
  const hdf5::Dataset r = fluence.open_dataset("r");
  EXPECT_TRUE(r.is_dimension_scale());
  EXPECT_EQ(r.read_string_attribute("units"), "mm");
  const std::vector<double> edges = spec.grid.r.edges();  // {0, 0.5, 1, 1.5}
  const hdf5::Array centres = r.read();
  ASSERT_EQ(centres.values.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(centres.values[i], 0.5 * (edges[i] + edges[i + 1]));
  }
  const hdf5::Dataset component = file.root().open_dataset("tallies/flux/component");
  EXPECT_TRUE(component.is_dimension_scale());
  EXPECT_EQ(component.read().values, (std::vector<double>{0, 1}));
  EXPECT_EQ(component.read_string_attribute("units"), "1");
  // A scalar has no dimension, so no scale.
  EXPECT_EQ(file.root().open_group("tallies/absorbed").member_names(),
            (std::vector<std::string>{"mean", "stderr"}));
}

TEST_F(SimulationFileTest, DefaultsOmitInfiniteEscapeRadiusAndName) {
  const fs::path path = directory_ / "defaults.h5";
  InfiniteMediumSpec spec;
  spec.medium.g = 0.0;
  write_simulation_file(path, spec, {scalar_tally("absorbed", 1.0, 0.0)}, small_provenance());

  const hdf5::File file = hdf5::File::open_read_only(path);
  const hdf5::Group parameters = file.root().open_group("parameters");
  EXPECT_FALSE(parameters.has_attribute("escape_radius"));
  EXPECT_EQ(parameters.read_string_attribute("phase"), "isotropic");
  EXPECT_EQ(parameters.read_string_attribute("source"), "beam");
  EXPECT_EQ(parameters.read_string_attribute("estimator"), "collision");
  EXPECT_EQ(parameters.read_int64_attribute("split_by_order"), 0);
  EXPECT_EQ(file.root().open_group("grid").read_int64_attribute("phi_folded"), 0);
  EXPECT_FALSE(file.root().has_member("grid/rho"));
  EXPECT_TRUE(file.root().has_member("grid/phi"));
  EXPECT_FALSE(file.root().has_member("no/such/path"));
}

TEST_F(SimulationFileTest, PaperSizedRadianceRoundTripsThroughCompression) {
  const fs::path path = directory_ / "large.h5";
  const InfiniteMediumSpec spec;  // the paper's grid: 15 x 40 x 18 x 36 bins
  const TallyResult radiance = array_tally(
      "radiance", {"r", "z", "theta", "phi"},
      {static_cast<std::size_t>(spec.grid.r.bins), static_cast<std::size_t>(spec.grid.z.bins),
       static_cast<std::size_t>(spec.grid.theta.bins),
       static_cast<std::size_t>(spec.grid.phi.bins)});
  ASSERT_GE(radiance.size(), hdf5::kChunkThreshold);
  write_simulation_file(path, spec, {radiance}, small_provenance());

  const hdf5::File file = hdf5::File::open_read_only(path);
  const hdf5::Array mean = file.root().read_dataset("tallies/radiance/mean");
  EXPECT_EQ(mean.shape, radiance.shape);
  EXPECT_EQ(mean.values, radiance.mean);
  EXPECT_EQ(file.root().read_dataset("tallies/radiance/stderr").values, radiance.stderr_of_mean);
}

TEST_F(SimulationFileTest, StringAttributesKeepUtf8) {
  const fs::path path = directory_ / "utf8.h5";
  {
    hdf5::File file = hdf5::File::create(path);
    file.root().write_string_attribute("units", "W mm⁻² sr⁻¹ per W, σ_t = 1");
    file.root().write_string_attribute("units", "µ ± σ");  // replaces
    file.close();
  }
  const hdf5::File file = hdf5::File::open_read_only(path);
  EXPECT_EQ(file.root().read_string_attribute("units"), "µ ± σ");
  EXPECT_EQ(file.root().attribute_names(), std::vector<std::string>{"units"});
}

TEST_F(SimulationFileTest, ExceptionBeforeCommitLeavesNothing) {
  const fs::path path = directory_ / "partial.h5";
  try {
    AtomicOutput output(path);
    hdf5::File file = hdf5::File::create(output.temporary_path());
    file.root().create_group("tallies/radiance");
    ASSERT_TRUE(fs::exists(output.temporary_path()));
    throw std::runtime_error("transport failed half way");
  } catch (const std::runtime_error&) {
  }
  EXPECT_TRUE(directory_entries().empty());
}

TEST_F(SimulationFileTest, InconsistentTallyLeavesNothing) {
  TallyResult broken = array_tally("fluence", {"r", "z"}, {3, 4});
  broken.stderr_of_mean.pop_back();
  EXPECT_THROW(
      write_simulation_file(directory_ / "broken.h5", small_spec(), {broken}, small_provenance()),
      std::invalid_argument);
  EXPECT_TRUE(directory_entries().empty());
}

TEST_F(SimulationFileTest, CommitLeavesOnlyTheFinalFileAndReplacesAnOldOne) {
  const fs::path path = directory_ / "run.h5";
  { std::ofstream(path) << "an older output"; }
  write_simulation_file(path, small_spec(), small_tallies(), small_provenance());
  EXPECT_EQ(directory_entries(), std::vector<std::string>{"run.h5"});
  EXPECT_TRUE(hdf5::is_hdf5_file(path));
}

TEST_F(SimulationFileTest, TemporaryPathIsBesideTheFinalOne) {
  const AtomicOutput output(directory_ / "run.h5");
  EXPECT_EQ(output.temporary_path().parent_path(), directory_);
  EXPECT_EQ(output.temporary_path().filename().string().rfind("run.h5.tmp-", 0), 0u);
  EXPECT_FALSE(output.committed());
}

TEST_F(SimulationFileTest, MissingOutputDirectoryIsAnInputErrorNamingOut) {
  const fs::path path = directory_ / "no-such-directory" / "run.h5";
  try {
    write_simulation_file(path, small_spec(), small_tallies(), small_provenance());
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.field(), "out");
    EXPECT_NE(std::string(error.what()).find("no-such-directory"), std::string::npos);
  }
  EXPECT_THROW(AtomicOutput{directory_}, InputError);  // a directory is not an output file
}

TEST_F(SimulationFileTest, DescribeSummarisesTheFile) {
  const fs::path path = directory_ / "run.h5";
  write_simulation_file(path, small_spec(), small_tallies(), small_provenance());
  const std::string text = describe_simulation_file(path);
  for (const char* expected :
       {"format      scatterlab, version 1", "scatterlab simulate --albedo 0.8",
        "2024-05-01T12:34:56Z", "wall time   12.5 s", "source", "track_length",
        "grid (phi folded onto [0, pi])", "theta", "radiance  [3 x 4 x 2 x 5] (r,z,theta,phi)",
        "median relative stderr", "absorbed  scalar", "0.75 ± 0.002"}) {
    EXPECT_NE(text.find(expected), std::string::npos) << expected << "\nin:\n" << text;
  }

  const FileSummary summary = read_file_summary(path);
  ASSERT_EQ(summary.tallies.size(), 3u);
  const TallySummary& fluence = summary.tallies[1];
  EXPECT_EQ(fluence.name, "fluence");
  const TallyResult expected = small_tallies()[1];
  double sum = 0.0;
  std::size_t nonzero = 0;
  for (const double value : expected.mean) {
    sum += value;
    nonzero += value != 0.0 ? 1 : 0;
  }
  EXPECT_DOUBLE_EQ(fluence.mean_sum, sum);
  EXPECT_EQ(fluence.nonzero_bins, nonzero);
  EXPECT_EQ(summary.grid.size(), 5u);
  EXPECT_EQ(summary.grid[0].bins, 3u);
}

// /models: a curve with its description, and its numerical error described as an error (not
// with the curve's own description); a model left out is a group with a note.
TEST_F(SimulationFileTest, ModelCurvesAndTheirErrorsSayWhatTheyHold) {
  const fs::path path = directory_ / "run.h5";
  const std::vector<ModelResult> models = {
      {"exact",
       "fluence",
       {"r", "z"},
       {3, 4},
       "mm^-2",
       "the exact fluence",
       std::vector<double>(12, 0.5),
       std::vector<double>(12, 1e-9)},
      {"dipole", "", {}, {}, "", "not evaluated: because", {}, {}}};
  write_simulation_file(path, small_spec(), small_tallies(), small_provenance(), models);
  const hdf5::File file = hdf5::File::open_read_only(path);
  const hdf5::Group exact = file.root().open_group("models/exact");
  const hdf5::Dataset curve = exact.open_dataset("fluence");
  const hdf5::Dataset error = exact.open_dataset("fluence_error");
  EXPECT_EQ(curve.read_string_attribute("description"), "the exact fluence");
  EXPECT_EQ(error.read_string_attribute("description"),
            "absolute numerical error estimate of fluence: the exact fluence");
  for (const hdf5::Dataset* dataset : {&curve, &error}) {
    EXPECT_EQ(dataset->read_string_attribute("units"), "mm^-2");
    EXPECT_EQ(dataset->read_string_attribute("dims"), "r,z");
  }
  EXPECT_EQ(file.root().open_group("models/dipole").read_string_attribute("note"),
            "not evaluated: because");
  // The model's group holds the scales of its curves' dimensions too, which are not curves.
  EXPECT_EQ(exact.member_names(), (std::vector<std::string>{"fluence", "fluence_error", "r", "z"}));
  EXPECT_EQ(curve_names(exact), (std::vector<std::string>{"fluence", "fluence_error"}));
}

void expect_not_a_simulation_file(const fs::path& path) {
  try {
    describe_simulation_file(path);
    FAIL() << "expected InputError for " << path;
  } catch (const InputError& error) {
    EXPECT_EQ(error.field(), "FILE");
    EXPECT_NE(std::string(error.what()).find("is not a scatterlab HDF5 file"), std::string::npos)
        << error.what();
    EXPECT_NE(std::string(error.what()).find(path.string()), std::string::npos) << error.what();
  }
}

TEST_F(SimulationFileTest, DescribeRefusesOtherFiles) {
  const fs::path foreign = directory_ / "foreign.h5";
  {
    hdf5::File file = hdf5::File::create(foreign);
    file.root().create_group("data").write_dataset("x", std::vector<double>{1.0, 2.0});
    file.close();
  }
  expect_not_a_simulation_file(foreign);

  const fs::path text = directory_ / "notes.txt";
  { std::ofstream(text) << "not HDF5 at all\n"; }
  expect_not_a_simulation_file(text);
  expect_not_a_simulation_file(directory_ / "missing.h5");
}

TEST_F(SimulationFileTest, Hdf5FailuresNameThePathAndTheOperation) {
  const fs::path text = directory_ / "notes.txt";
  { std::ofstream(text) << "not HDF5 at all\n"; }
  try {
    hdf5::File::open_read_only(text);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("open file"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find(text.string()), std::string::npos) << error.what();
  }

  const fs::path path = directory_ / "run.h5";
  write_simulation_file(path, small_spec(), small_tallies(), small_provenance());
  const hdf5::File file = hdf5::File::open_read_only(path);
  try {
    file.root().open_group("parameters").read_double_attribute("no_such_attribute");
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("'no_such_attribute'"), std::string::npos) << message;
    EXPECT_NE(message.find(path.string() + ":/parameters"), std::string::npos) << message;
  }
  EXPECT_THROW(file.root().open_group("parameters").read_double_attribute("source"),
               std::runtime_error);  // a string is not a number
  EXPECT_THROW(file.root().open_dataset("tallies"), std::runtime_error);
}

TEST(Iso8601Now, IsUtcWithSecondResolution) {
  const std::string now = iso8601_now();
  ASSERT_EQ(now.size(), 20u) << now;
  EXPECT_EQ(now[4], '-');
  EXPECT_EQ(now[10], 'T');
  EXPECT_EQ(now[19], 'Z');
}

}  // namespace
}  // namespace scatterlab
