#include "scatterlab/io/checkpoint_file.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fnv1a.hpp"
#include "scatterlab/io/atomic_output.hpp"
#include "scatterlab/io/hdf5_file.hpp"
#include "scatterlab/io/simulation_file.hpp"

namespace scatterlab {
namespace {

constexpr const char* kFormat = "scatterlab-checkpoint";
// 2: with the checksum; a version 1 checkpoint, which has none, cannot be trusted and is refused.
constexpr std::int64_t kFormatVersion = 2;

std::int64_t as_int64(std::uint64_t value) {
  if (value > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
    throw std::invalid_argument("checkpoint: count does not fit in int64");
  }
  return static_cast<std::int64_t>(value);
}

// What makes a saved state unusable, whatever run it is resumed into (the runner checks that it
// fits the run: batches and cell count); empty when nothing does.
std::string state_problem(std::int64_t batches_folded, std::int64_t scattering_events,
                          const RunState& state) {
  if (batches_folded < 1) return fmt::format("batches_folded is {}, not 1 or more", batches_folded);
  if (scattering_events < 0) {
    return fmt::format("scattering_events is {}, not 0 or more", scattering_events);
  }
  if (!std::isfinite(state.wall_seconds) || state.wall_seconds < 0.0) {
    return fmt::format("wall_seconds is {}, not a finite number >= 0", state.wall_seconds);
  }
  if (state.mean.empty() || state.mean.size() != state.squares.size()) {
    return fmt::format("welford_mean holds {} values and welford_squares {}, not the same number",
                       state.mean.size(), state.squares.size());
  }
  for (std::size_t i = 0; i < state.mean.size(); ++i) {
    if (!std::isfinite(state.mean[i])) {
      return fmt::format("welford_mean[{}] is {}, not a finite number", i, state.mean[i]);
    }
    // Sums of squared deviations: never negative, and zero after a single batch.
    const double square = state.squares[i];
    if (!std::isfinite(square) || square < 0.0 || (batches_folded == 1 && square != 0.0)) {
      return fmt::format("welford_squares[{}] is {}, not a finite number >= 0{}", i, square,
                         batches_folded == 1 ? " (0 after one batch)" : "");
    }
  }
  return {};
}

// The checksum of everything a resumed run takes from the file, in the order written: a file
// whose fingerprint matches but whose counts or values were edited since is refused.
std::string state_checksum(const std::string& spec_fingerprint, std::int64_t batches_folded,
                           std::int64_t scattering_events, const RunState& state) {
  Fnv1a hash;
  hash.add(spec_fingerprint);
  hash.add_bytes_of(std::span<const std::int64_t>(&batches_folded, 1));
  hash.add_bytes_of(std::span<const std::int64_t>(&scattering_events, 1));
  hash.add_bytes_of(std::span<const double>(&state.wall_seconds, 1));
  hash.add_bytes_of(std::span<const double>(state.mean));
  hash.add_bytes_of(std::span<const double>(state.squares));
  return fmt::format("{:016x}", hash.value());
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
    const std::int64_t batches_folded = as_int64(state.batches_folded);
    const std::int64_t scattering_events = as_int64(state.scattering_events);
    root.write_int64_attribute("batches_folded", batches_folded);
    root.write_int64_attribute("scattering_events", scattering_events);
    root.write_double_attribute("wall_seconds", state.wall_seconds);
    root.write_string_attribute(
        "checksum", state_checksum(spec_fingerprint, batches_folded, scattering_events, state));
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
    const std::int64_t version =
        root.has_attribute("format_version") ? root.read_int64_attribute("format_version") : 0;
    if (version != kFormatVersion) {
      throw InputError(field,
                       fmt::format("'{}' has checkpoint format_version {}, this scatterlab reads "
                                   "{}{}",
                                   path.string(), version, kFormatVersion,
                                   version == 1 ? " (version 1 has no checksum: run again "
                                                  "without --resume)"
                                                : ""),
                       accepted);
    }
    RunState state;
    const std::int64_t batches_folded = root.read_int64_attribute("batches_folded");
    const std::int64_t scattering_events = root.read_int64_attribute("scattering_events");
    state.mean = root.read_dataset("welford_mean").values;
    state.squares = root.read_dataset("welford_squares").values;
    state.wall_seconds = root.read_double_attribute("wall_seconds");
    const std::string stored = root.read_string_attribute("checksum");
    if (stored != state_checksum(written_for, batches_folded, scattering_events, state)) {
      throw InputError(field,
                       fmt::format("the checkpoint '{}' was changed after it was written: its "
                                   "checksum {} does not match what it holds",
                                   path.string(), stored),
                       accepted);
    }
    const std::string problem = state_problem(batches_folded, scattering_events, state);
    if (!problem.empty()) {
      throw InputError(field,
                       fmt::format("the checkpoint '{}' is damaged: {}", path.string(), problem),
                       accepted);
    }
    state.batches_folded = static_cast<std::uint64_t>(batches_folded);
    state.scattering_events = static_cast<std::uint64_t>(scattering_events);
    return state;
  } catch (const InputError&) {
    throw;
  } catch (const std::runtime_error& failure) {
    throw InputError(field, fmt::format("cannot read '{}': {}", path.string(), failure.what()),
                     accepted);
  }
}

}  // namespace scatterlab
