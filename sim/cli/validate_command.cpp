// scatterlab validate deon: d'Eon & Irving 2011's point-source fluence comparison (Vavassori
// §4.1 Fig. 4.2, §4.4) — Monte Carlo, the exact solution, classical diffusion and Grosjean for
// albedos 0.01 to 0.99, g = 0 — as an error table on stdout, CSV tables and PNG plots.
#include <fmt/format.h>

#include <chrono>
#include <memory>
#include <cmath>
#include <vector>

#include "commands.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/validate/point_source_comparison.hpp"
#include "scatterlab/validate/validation_report.hpp"

namespace scatterlab::cli {
namespace {

struct ValidateOptions {
  std::string out = "validate-deon";
  double photons = 1e6;  // a double so that 1e6 reads as in scene files
  bool quick = false;
  int threads = 0;
  std::uint64_t seed = 1;
};

std::uint64_t photon_count(double photons) {
  if (!(photons >= 1000.0) || photons > 1e12 || std::floor(photons) != photons) {
    throw InputError("photons", fmt::format("got {}", photons), "a whole number in [1000, 1e12]");
  }
  return static_cast<std::uint64_t>(photons);
}

int run_deon(const ValidateOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  PointSourceComparisonSettings settings;
  settings.photons = options.quick ? 20'000 : photon_count(options.photons);
  settings.threads = options.threads;
  settings.seed = options.seed;
  if (options.threads < 0) throw InputError("threads", "negative", "0 (all) or a positive count");
  const std::vector<double> albedos = {0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99};
  std::vector<PointSourceComparison> comparisons;
  for (std::size_t i = 0; i < albedos.size(); ++i) {
    // A seed per albedo: with one seed the albedos share their first flights, and a fluctuation
    // in one shell repeats in every row of the table.
    PointSourceComparisonSettings per_albedo = settings;
    per_albedo.seed = settings.seed + i;
    comparisons.push_back(compare_point_source(albedos[i], per_albedo));
  }
  const auto files = write_point_source_report(comparisons, options.out);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print("scatterlab validate deon: isotropic point source, g = 0, {} photons per albedo, "
             "shells of {} mfp to {} mfp\n",
             settings.photons, settings.rho.width(), settings.rho.max);
  fmt::print("mean relative error of shell-averaged fluence against the exact solution, near "
             "(r < 1 mfp) / far (r >= 1 mfp):\n{}",
             point_source_error_table(comparisons));
  fmt::print("  {:.2f} s; wrote {} files to {}\n", seconds, files.size(), options.out);
  return 0;
}

}  // namespace

Action add_validate_command(CLI::App& app) {
  auto options = std::make_shared<ValidateOptions>();
  CLI::App* validate = app.add_subcommand(
      "validate", "Compare the analytic models and the exact solutions against Monte Carlo");
  validate->require_subcommand(1);
  CLI::App* deon = validate->add_subcommand(
      "deon",
      "Point-source fluence r^2 phi(r) for albedos 0.01-0.99: Monte Carlo, exact, diffusion, "
      "Grosjean (d'Eon & Irving 2011); error table, CSV and PNG plots");
  deon->add_option("--out", options->out, "Directory for the CSV and PNG files (created if missing)")
      ->capture_default_str();
  deon->add_option("--photons", options->photons, "Photons per albedo")->capture_default_str();
  deon->add_flag("--quick", options->quick, "2e4 photons per albedo, for tests");
  deon->add_option("--threads", options->threads, "Threads (0: all hardware threads)")
      ->capture_default_str();
  deon->add_option("--seed", options->seed, "Random seed")->capture_default_str();
  return [options, deon] {
    if (deon->parsed()) return run_deon(*options);
    return 1;
  };
}

}  // namespace scatterlab::cli
