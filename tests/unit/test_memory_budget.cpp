// Memory and time known before a run starts: the memory limit and its sizes
// (core/memory_budget.hpp), the estimates of the transport and the renderer, the HDF5 reader's
// check of a dataset's declared shape (io/hdf5_file.hpp), and the bounds on runs that would never
// finish: photon counts, events per photon (transport/run_settings.hpp) and sweep sizes
// (io/scene.hpp).
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "input_error_field.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/memory_budget.hpp"
#include "scatterlab/io/hdf5_file.hpp"
#include "scatterlab/io/scene.hpp"
#include "scatterlab/io/simulation_file.hpp"
#include "scatterlab/transport/engine.hpp"
#include "scatterlab/transport/run_settings.hpp"
#include "scatterlab/transport/searchlight.hpp"
#include "scatterlab/transport/simulate.hpp"

namespace scatterlab {
namespace {

namespace fs = std::filesystem;

using test_support::field_of;

// Sets --memory-limit for one test and restores the machine's limit after it.
struct ScopedMemoryLimit {
  explicit ScopedMemoryLimit(std::uint64_t bytes) { set_memory_limit(bytes, "test"); }
  ~ScopedMemoryLimit() { set_memory_limit(std::nullopt); }
};

constexpr std::uint64_t MiB = std::uint64_t{1} << 20;
constexpr std::uint64_t GiB = std::uint64_t{1} << 30;

TEST(MemoryBudget, SizesReadAsPowersOf1024) {
  EXPECT_EQ(parse_memory_size("512M", "--memory-limit"), 512 * MiB);
  EXPECT_EQ(parse_memory_size("4G", "--memory-limit"), 4 * GiB);
  EXPECT_EQ(parse_memory_size("4g", "--memory-limit"), 4 * GiB);
  EXPECT_EQ(parse_memory_size("4GB", "--memory-limit"), 4 * GiB);
  EXPECT_EQ(parse_memory_size("1.5GiB", "--memory-limit"), 3 * GiB / 2);
  EXPECT_EQ(parse_memory_size("2T", "--memory-limit"), 2048 * GiB);
  EXPECT_EQ(parse_memory_size("64K", "--memory-limit"), 64 * 1024);
  EXPECT_EQ(parse_memory_size("1000000", "--memory-limit"), 1000000u);
  EXPECT_EQ(parse_memory_size("300B", "--memory-limit"), 300u);
  for (const char* bad : {"", "M", "abc", "0", "0.1", "-1", "4X", "4 G", "1e3", "1..5G", ".",
                          "9000000000T", "4GiBs", "nan", "inf"}) {
    EXPECT_EQ(field_of([&] { parse_memory_size(bad, "--memory-limit"); }), "--memory-limit") << bad;
  }
}

TEST(MemoryBudget, BytesPrintInBinaryUnits) {
  EXPECT_EQ(format_bytes(300), "300 B");
  EXPECT_EQ(format_bytes(512 * MiB), "512.0 MiB");
  EXPECT_EQ(format_bytes(80 * GiB + GiB / 10), "80.1 GiB");
  EXPECT_EQ(format_bytes(std::numeric_limits<std::uint64_t>::max()), "more than 16 EiB");
}

TEST(MemoryBudget, EstimatesSaturateInsteadOfWrapping) {
  MemoryEstimate need;
  need.add_doubles("huge", std::uint64_t{1} << 62, 4);
  need.add("more", 1);
  EXPECT_EQ(need.bytes(), std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(saturating_product(std::uint64_t{1} << 40, std::uint64_t{1} << 40),
            std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(saturating_product(0, std::numeric_limits<std::uint64_t>::max()), 0u);
}

TEST(MemoryBudget, MachineLimitIsPhysicalMemoryOrLower) {
  const MemoryLimit machine = machine_memory_limit();
  EXPECT_GT(machine.bytes, 16 * MiB);
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  EXPECT_LE(machine.bytes, static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page));
  EXPECT_EQ(memory_limit().bytes, machine.bytes);
  const ScopedMemoryLimit limit(512 * MiB);
  EXPECT_EQ(memory_limit().bytes, 512 * MiB);
  EXPECT_NE(memory_limit().source.find("--memory-limit"), std::string::npos);
}

TEST(MemoryBudget, OverTheLimitIsOneErrorNamingFieldsAndFigure) {
  const ScopedMemoryLimit limit(GiB);
  MemoryEstimate need;
  need.add_doubles("score buffers", 100 * MiB, 2);
  try {
    check_memory(need, "grid.r.bins x grid.z.bins", "fewer bins");
    FAIL() << "1.6 GiB fitted in 1 GiB";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "grid.r.bins x grid.z.bins");
    const std::string message = e.what();
    EXPECT_NE(message.find("1.6 GiB for 2 x score buffers"), std::string::npos) << message;
    EXPECT_NE(message.find("over --memory-limit test (1.0 GiB)"), std::string::npos) << message;
    EXPECT_NE(message.find("accepted: fewer bins to fit in 1.0 GiB; or --memory-limit SIZE of at "
                           "least 1.6 GiB"),
              std::string::npos)
        << message;
  }
  MemoryEstimate small;
  small.add_doubles("score buffers", MiB, 2);
  EXPECT_NO_THROW(check_memory(small, "grid", "fewer bins"));
}

// A grid within every per-axis limit (1e5 bins) whose fluence alone is 1e10 cells, 80 GB per
// array: refused with the figure before the first buffer, never std::bad_alloc.
TEST(MemoryBudget, SimulationGridWithinAxisLimitsButOverMemoryIsRefused) {
  InfiniteMediumSpec spec;
  spec.tallies.radiance = false;
  spec.tallies.flux = false;
  spec.grid.r.bins = 100000;
  spec.grid.z.bins = 100000;
  spec.run.photons = 1000;
  spec.run.batches = 10;
  spec.run.threads = 1;
  ASSERT_NO_THROW(spec.validate());
  const MemoryEstimate need = transport_memory(transport_problem(spec), 1, false);
  EXPECT_GT(need.bytes(), 6 * 80'000'000'000ull);  // a buffer per thread and five arrays
  EXPECT_EQ(field_of([&] { run_infinite_medium(spec); }),
            "grid.r.bins x grid.z.bins, tallies, run.threads");
  const ScopedMemoryLimit limit(512 * MiB);
  InfiniteMediumSpec paper;
  paper.run.photons = 1000;
  paper.run.batches = 10;
  EXPECT_EQ(field_of([&] { check_transport_memory(transport_problem(paper), 1, false); }), "");
  paper.tallies.split_by_order = true;
  paper.grid.r.bins = 150;
  EXPECT_EQ(field_of([&] { check_transport_memory(transport_problem(paper), 1, false); }),
            "grid.r.bins x grid.z.bins x grid.theta.bins x grid.phi.bins, tallies, "
            "tallies.split_by_order, run.threads");
}

TEST(MemoryBudget, EveryThreadAndRankAddsItsBuffers) {
  InfiniteMediumSpec spec;
  spec.run.batches = 64;
  spec.run.threads = 1;
  const std::uint64_t one = transport_memory(transport_problem(spec), 1, false).bytes();
  spec.run.threads = 8;
  const std::uint64_t eight = transport_memory(transport_problem(spec), 1, false).bytes();
  const std::uint64_t ranks = transport_memory(transport_problem(spec), 4, false).bytes();
  const std::uint64_t resumed = transport_memory(transport_problem(spec), 1, true).bytes();
  const std::uint64_t cells = 15 * 40 * (18 * 36 + 1 + 2) + 3;  // radiance, fluence, flux, scalars
  EXPECT_EQ(eight - one, 14 * cells * sizeof(double));  // a ring of 2 x 8 - 1 buffers, not 1
  EXPECT_EQ(ranks - eight, cells * sizeof(double));     // a group's received slices
  EXPECT_EQ(resumed - eight, 2 * cells * sizeof(double));
}

TEST(MemoryBudget, SearchlightFluenceOverMemoryIsRefused) {
  HalfSpaceSpec spec;
  spec.grid.r.bins = 100000;
  spec.grid.z.bins = 100000;
  spec.run.photons = 1000;
  spec.run.batches = 10;
  spec.run.threads = 1;
  ASSERT_NO_THROW(spec.validate());
  EXPECT_EQ(field_of([&] { run_half_space(spec); }),
            "grid.r.bins x grid.z.bins (fluence), grid.theta_o.bins, run.threads");
}

TEST(RunLength, PhotonsStayExactAsDoubles) {
  InfiniteMediumSpec spec;
  spec.medium.albedo = 0.0;
  spec.run.photons = max_photons;
  EXPECT_EQ(field_of([&] { spec.validate(); }), "");
  spec.run.photons = max_photons + 1;
  EXPECT_EQ(field_of([&] { spec.validate(); }), "run.photons");
  spec.run.photons = std::uint64_t{1} << 63;
  EXPECT_EQ(field_of([&] { spec.validate(); }), "run.photons");
}

TEST(RunLength, ExpectedEventsPerPhotonAreBounded) {
  EXPECT_DOUBLE_EQ(expected_events_per_photon(0.5, std::numeric_limits<double>::infinity()), 2.0);
  EXPECT_DOUBLE_EQ(expected_events_per_photon(1.0, 100.0), 10001.0);
  EXPECT_DOUBLE_EQ(expected_events_per_photon(0.99, 1000.0), 1.0 / (1.0 - 0.99));

  InfiniteMediumSpec spec;  // albedo 1 with an escape radius of 1e30 mfp: ~1e60 events per photon
  spec.medium.albedo = 1.0;
  spec.run.photons = 1000;
  spec.run.batches = 10;
  spec.run.escape_radius = 1e30;
  EXPECT_EQ(field_of([&] { spec.validate(); }), "medium.albedo, run.escape_radius");
  spec.run.escape_radius = 1000.0;  // 1e6 events per photon: 1e9 in all
  EXPECT_EQ(field_of([&] { spec.validate(); }), "");
  spec.run.photons = 100'000'000'000;  // 1e17 events in all
  EXPECT_EQ(field_of([&] { spec.validate(); }), "run.photons");
  // Albedo near 1 without an escape radius: 1 / (1 - albedo) events each.
  spec.run.escape_radius = std::numeric_limits<double>::infinity();
  spec.medium.albedo = 1.0 - 1e-12;
  spec.run.photons = 100'000;
  EXPECT_EQ(field_of([&] { spec.validate(); }), "run.photons");
  spec.run.photons = 1000;
  EXPECT_EQ(field_of([&] { spec.validate(); }), "");

  HalfSpaceSpec half_space;
  half_space.medium.albedo = 1.0;
  half_space.run.photons = 1000;
  half_space.run.batches = 10;
  half_space.run.escape_radius = 1e30;
  EXPECT_EQ(field_of([&] { half_space.validate(); }), "medium.albedo, run.escape_radius");
  half_space.run.escape_radius = 1e7;  // 1e14 events per photon, 1e17 in all

  EXPECT_EQ(field_of([&] { half_space.validate(); }), "run.photons");
}

TEST(SweepSize, CountedFromTheListsBeforeAnyPointIsMade) {
  // 100000 x 100000 combinations: expanding first would never end; refused at once.
  std::string albedos = "[", gs = "[";
  for (int i = 0; i < 100000; ++i) {
    albedos += fmt::format("{}0.{:05d}", i ? "," : "", i);
    gs += fmt::format("{}0.{:05d}", i ? "," : "", i);
  }
  const std::string text = fmt::format("[medium]\nalbedo = {}]\ng = {}]\n", albedos, gs);
  const auto start = std::chrono::steady_clock::now();
  try {
    parse_sweep(text, "big.toml");
    FAIL() << "a sweep of 1e10 points was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "medium.albedo x medium.g");
    EXPECT_NE(std::string(e.what()).find("100000 x 100000 = 10000000000 combinations"),
              std::string::npos)
        << e.what();
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
}

TEST(SweepSize, TheLimitItselfIsAccepted) {
  std::string seeds = "[";
  for (std::uint64_t i = 0; i < max_sweep_points; ++i)
    seeds += fmt::format("{}{}", i ? "," : "", i + 1);
  const std::vector<SweepPoint> points =
      parse_sweep("[run]\nseed = " + seeds + "]\n", "seeds.toml");
  ASSERT_EQ(points.size(), max_sweep_points);
  EXPECT_EQ(std::get<InfiniteMediumSpec>(points.back().scene.spec).run.seed, max_sweep_points);
  EXPECT_EQ(field_of([&] { parse_sweep("[run]\nseed = " + seeds + ",0]\n", "seeds.toml"); }),
            "run.seed");
}

// A file of a few kB whose dataset declares 1e6 x 1e6 doubles (8 TB) in chunks never written.
fs::path crafted_file(const std::string& name) {
  const fs::path path = fs::temp_directory_path() / fmt::format("{}-{}.h5", name, getpid());
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t dims[2] = {1'000'000, 1'000'000}, chunk[2] = {64, 64};
  const hid_t space = H5Screate_simple(2, dims, nullptr);
  const hid_t plist = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(plist, 2, chunk);
  const hid_t group = H5Gcreate2(file, "tallies", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t dataset =
      H5Dcreate2(group, "mean", H5T_IEEE_F64LE, space, H5P_DEFAULT, plist, H5P_DEFAULT);
  const double one = 1.0;
  const hsize_t start[2] = {0, 0}, count[2] = {1, 1};
  const hid_t memory = H5Screate_simple(2, count, nullptr);
  H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr);
  H5Dwrite(dataset, H5T_NATIVE_DOUBLE, memory, space, H5P_DEFAULT, &one);
  H5Sclose(memory);
  H5Dclose(dataset);
  H5Gclose(group);
  H5Pclose(plist);
  H5Sclose(space);
  H5Fclose(file);
  return path;
}

TEST(DeclaredShape, DatasetLargerThanItsFileIsRefusedBeforeAllocating) {
  const fs::path path = crafted_file("declared-8TB");
  ASSERT_LT(fs::file_size(path), 100'000u);
  try {
    const hdf5::File file = hdf5::File::open_read_only(path);
    (void)file.root().read_dataset("tallies/mean");
    FAIL() << "an 8 TB dataset was read";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("[1000000 x 1000000]"), std::string::npos) << message;
    EXPECT_NE(message.find(path.string() + ":/tallies/mean"), std::string::npos) << message;
  }
  fs::remove(path);
}

TEST(DeclaredShape, DatasetOverTheMemoryLimitNamesFileAndDataset) {
  const fs::path path = fs::temp_directory_path() / fmt::format("declared-2MiB-{}.h5", getpid());
  {
    hdf5::File file = hdf5::File::create(path);
    std::vector<double> values(256 * 1024);  // 2 MiB that deflate cannot shrink much
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = std::sin(static_cast<double>(i));
    file.root().write_dataset("values", values);
    file.close();
  }
  {
    const hdf5::File file = hdf5::File::open_read_only(path);
    EXPECT_EQ(file.root().read_dataset("values").values.size(), 256u * 1024u);
    const ScopedMemoryLimit limit(MiB);
    EXPECT_EQ(field_of([&] { (void)file.root().read_dataset("values"); }),
              path.string() + ":/values");
  }
  fs::remove(path);
}

}  // namespace
}  // namespace scatterlab
