#include "scatterlab/io/checkpoint_file.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <limits>
#include <stdexcept>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/atomic_output.hpp"
#include "scatterlab/io/hdf5_file.hpp"
#include "scatterlab/io/simulation_file.hpp"

namespace scatterlab {
namespace {

constexpr const char* kFormat = "scatterlab-checkpoint";
constexpr std::int64_t kFormatVersion = 1;

std::int64_t as_int64(std::uint64_t value) {
  if (value > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
    throw std::invalid_argument("checkpoint: count does not fit in int64");
  }
  return static_cast<std::int64_t>(value);
}

}  // namespace

std::filesystem::path default_checkpoint_path(const std::filesystem::path& output) {
  std::filesystem::path path = output;
  path += ".checkpoint";
  return path;
}

void write_checkpoint(const std::filesystem::path& path, const std::string& spec_fingerprint,
                      const RunState& state) {
  AtomicOutput output(path);
  {
    hdf5::File file = hdf5::File::create(output.temporary_path());
    hdf5::Group& root = file.root();
    root.write_string_attribute("format", kFormat);
    root.write_int64_attribute("format_version", kFormatVersion);
    root.write_string_attribute("spec_fingerprint", spec_fingerprint);
    root.write_int64_attribute("batches_folded", as_int64(state.batches_folded));
    root.write_int64_attribute("scattering_events", as_int64(state.scattering_events));
    root.write_string_attribute("created", iso8601_now());
    root.write_dataset("welford_mean", state.mean);
    root.write_dataset("welford_squares", state.squares);
    file.close();
  }
  output.commit();
}

bool is_checkpoint_of(const std::filesystem::path& path, const std::string& spec_fingerprint) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error) || !hdf5::is_hdf5_file(path)) return false;
  try {
    const hdf5::File file = hdf5::File::open_read_only(path);
    const hdf5::Group& root = file.root();
    return root.has_attribute("format") && root.read_string_attribute("format") == kFormat &&
           root.has_attribute("spec_fingerprint") &&
           root.read_string_attribute("spec_fingerprint") == spec_fingerprint;
  } catch (const std::exception&) {
    return false;
  }
}

RunState read_checkpoint(const std::filesystem::path& path, const std::string& spec_fingerprint,
                         const std::string& field) {
  const std::string accepted = "a checkpoint written by the same run (same parameters and seed)";
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw InputError(field, fmt::format("no checkpoint at '{}'", path.string()), accepted);
  }
  if (!hdf5::is_hdf5_file(path)) {
    throw InputError(field, fmt::format("'{}' is not an HDF5 file", path.string()), accepted);
  }
  try {
    const hdf5::File file = hdf5::File::open_read_only(path);
    const hdf5::Group& root = file.root();
    if (!root.has_attribute("format") || root.read_string_attribute("format") != kFormat) {
      throw InputError(field, fmt::format("'{}' is not a scatterlab checkpoint", path.string()),
                       accepted);
    }
    const std::string written_for = root.read_string_attribute("spec_fingerprint");
    if (written_for != spec_fingerprint) {
      throw InputError(field,
                       fmt::format("'{}' was written by a run with other parameters or seed "
                                   "(fingerprint {}, this run {})",
                                   path.string(), written_for, spec_fingerprint),
                       accepted);
    }
    RunState state;
    state.batches_folded = static_cast<std::uint64_t>(root.read_int64_attribute("batches_folded"));
    state.scattering_events =
        static_cast<std::uint64_t>(root.read_int64_attribute("scattering_events"));
    state.mean = root.read_dataset("welford_mean").values;
    state.squares = root.read_dataset("welford_squares").values;
    if (state.mean.size() != state.squares.size()) {
      throw std::runtime_error("welford_mean and welford_squares differ in size");
    }
    return state;
  } catch (const InputError&) {
    throw;
  } catch (const std::runtime_error& failure) {
    throw InputError(field, fmt::format("cannot read '{}': {}", path.string(), failure.what()),
                     accepted);
  }
}

}  // namespace scatterlab
