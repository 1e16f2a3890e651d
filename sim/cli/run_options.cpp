#include "run_options.hpp"

#include <fmt/format.h>

#include "commands.hpp"

namespace scatterlab::cli {

RunOptions run_options_of(const RunSettings& run) {
  return {static_cast<double>(run.photons), run.batches, run.seed, run.threads, run.escape_radius};
}

void add_run_options(CLI::App& command, RunOptions& o) {
  command.add_option("--photons", o.photons,
                     "Number of photons, at most 2^53 (counts exact as doubles); with the "
                     "expected events per photon, min(1 / (1 - albedo), 1 + (escape radius in "
                     "mfp)^2), at most 2^53 events in all (years on one thread)");
  command.add_option("--batches", o.batches, "Batches for the standard error, >= 2");
  command.add_option("--seed", o.seed, "Random seed, in [0, 2^63 - 1]");
  command.add_option("--threads", o.threads, threads_help());
  command.add_option("--escape-radius", o.escape_radius,
                     "Stop photons beyond this distance (in the length unit); needed for albedo 1");
}

std::string threads_help() {
  return fmt::format(
      "Threads, in [0, {}]: at most 4 per hardware thread; 0 uses all cores "
      "(OMP_NUM_THREADS if set, held to the same bound)",
      max_threads());
}

void apply_run_options(const CLI::App& command, const RunOptions& o, RunSettings& run) {
  auto given = [&command](const char* flag) { return command.get_option(flag)->count() > 0; };
  if (given("--photons")) run.photons = photon_count(o.photons);
  if (given("--batches")) run.batches = o.batches;
  if (given("--seed")) {
    check_seed(o.seed, "--seed");
    run.seed = o.seed;
  }
  if (given("--threads")) {
    check_threads(o.threads, "--threads");
    run.threads = o.threads;
  }
  if (given("--escape-radius")) run.escape_radius = o.escape_radius;
}

}  // namespace scatterlab::cli
