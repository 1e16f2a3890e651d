#pragma once
// The batch-run flags every transport command shares (--photons, --batches, --seed, --threads,
// --escape-radius): registered once, and laid over the scene's RunSettings where given.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

#include "scatterlab/transport/run_settings.hpp"

namespace scatterlab::cli {

struct RunOptions {
  double photons = 0;  // a double, so that 1e8 reads as it does in scene files
  std::uint32_t batches = 0;
  std::uint64_t seed = 0;
  int threads = 0;
  double escape_radius = 0;
};

// The flags at a command's built-in run settings, which --help shows as the defaults.
RunOptions run_options_of(const RunSettings& run);

// Registers the flags, read into `options`.
void add_run_options(CLI::App& command, RunOptions& options);

// The help text of every command's --threads: the bound and what 0 means (run_settings.hpp).
std::string threads_help();

// The flags given on the command line override `run`; throws InputError for a bad photon count,
// and for a seed or thread count out of range, naming the flag (the same checks as the scene's).
void apply_run_options(const CLI::App& command, const RunOptions& options, RunSettings& run);

}  // namespace scatterlab::cli
