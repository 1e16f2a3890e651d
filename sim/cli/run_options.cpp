#include "run_options.hpp"

#include "commands.hpp"

namespace scatterlab::cli {

void add_run_options(CLI::App& command, RunOptions& o, const std::string& default_photons) {
  command.add_option("--photons", o.photons, "Number of photons [" + default_photons + "]");
  command.add_option("--batches", o.batches, "Batches for the standard error, >= 2 [64]");
  command.add_option("--seed", o.seed, "Random seed [1]");
  command.add_option("--threads", o.threads, "Threads; 0 uses all cores [0]");
  command.add_option(
      "--escape-radius", o.escape_radius,
      "Stop photons beyond this distance (in the length unit); needed for albedo 1 [inf]");
}

void apply_run_options(const CLI::App& command, const RunOptions& o, RunSettings& run) {
  auto given = [&command](const char* flag) { return command.get_option(flag)->count() > 0; };
  if (given("--photons")) run.photons = photon_count(o.photons);
  if (given("--batches")) run.batches = o.batches;
  if (given("--seed")) run.seed = o.seed;
  if (given("--threads")) run.threads = o.threads;
  if (given("--escape-radius")) run.escape_radius = o.escape_radius;
}

}  // namespace scatterlab::cli
