// scatterlab fit: lobe models fitted to every spatial bin of a simulation file (Vavassori §4.2),
// written back into the file under /fits/<model> and summarised in a CSV file.
#include <fmt/format.h>

#include <filesystem>
#include <memory>

#include "commands.hpp"
#include "log_interval_option.hpp"
#include "memory_limit_option.hpp"
#include "prepare_outputs.hpp"
#include "progress_reporter.hpp"
#include "run_options.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/fit/field_table.hpp"
#include "scatterlab/fit/lobe_fits_file.hpp"

namespace scatterlab::cli {

namespace {

struct FitCommandOptions {
  std::string path;
  std::string models = "sg,sg_free,dexp_paper,dexp,adexp,asg,adexp_ridge,adexp2_ridge";
  std::string csv;
  int threads = 0;
  int quadrature = 3;
};

}  // namespace

Action add_fit_command(CLI::App& app) {
  auto* command = app.add_subcommand("fit", kFitDescription);
  auto options = std::make_shared<FitCommandOptions>();
  command
      ->add_option("FILE", options->path,
                   "File written by scatterlab simulate (radiance tally), or a sweep directory "
                   "(simulate --out DIR): every .h5 file in it, and one table of parameters "
                   "against (r, z, albedo, g)")
      ->required();
  command->add_option(
      "--models", options->models,
      "Comma-separated: sg (spherical Gaussian, axis E), sg_free (axis fitted), "
      "dexp_paper (the paper's four-step double-exponential estimate, not solved), "
      "dexp (double exponential), adexp (anisotropic double exponential), asg "
      "(anisotropic spherical Gaussian, Xu et al. 2013), adexp_ridge (adexp plus the "
      "ridge of once-scattered light on phi = 0), adexp2_ridge (adexp_ridge plus a second "
      "adexp)");
  command
      ->add_option("--csv", options->csv,
                   "Summary CSV path; for a directory DIR, DIR/fits-table.csv by default")
      ->default_str("FILE-fits.csv");
  command->add_option("--threads", options->threads, threads_help());
  add_memory_limit_option(*command);
  const auto log_interval = add_log_interval_option(*command);
  command->add_option("--quadrature", options->quadrature,
                      "Gauss-Legendre points per angular bin and axis that average a model over "
                      "the bin, in [1, 8]");
  return [options, log_interval] {
    const std::vector<fit::LobeModel> models = fit::parse_lobe_models(options->models);
    check_threads(options->threads, "--threads");
    if (options->quadrature < 1 || options->quadrature > 8) {
      throw InputError("quadrature", std::to_string(options->quadrature), "an integer in [1, 8]");
    }
    const fit::FitOptions fit_options;
    ProgressReporter reporter("fit", "bins", *log_interval);
    const WorkProgress progress = [&reporter](std::uint64_t done, std::uint64_t bins) {
      reporter.update(done, bins);
    };
    if (std::filesystem::is_directory(options->path)) {
      // A sweep directory: one table of parameters against (r, z, albedo, g) (field_table.hpp).
      const std::filesystem::path table =
          options->csv.empty() ? std::filesystem::path(options->path) / "fits-table.csv"
                               : std::filesystem::path(options->csv);
      OutputPlan plan;
      for (const auto& file : fit::sweep_files(options->path)) plan.rewritten_input("FILE", file);
      plan.output_file("--csv", table);
      prepare_outputs(plan);
      const fit::FieldFit field = fit::fit_field(options->path, table, models, fit_options,
                                                 options->quadrature, options->threads, progress);
      reporter.finish();
      for (std::size_t f = 0; f < field.files.size(); ++f) {
        const fit::RadianceLobes& lobes = field.files[f];
        fmt::print("scatterlab fit: {} (albedo {}, g {})\n", lobes.path.string(), lobes.albedo,
                   lobes.g);
        fmt::print("{}", fit::describe(fit::summarize(field.runs[f]), field.runs[f]));
      }
      fmt::print("  wrote /fits/{{{}}} in {} files and the table {}\n", options->models,
                 field.files.size(), table.string());
      return 0;
    }
    const std::filesystem::path csv = options->csv.empty() ? fit::default_fits_csv(options->path)
                                                           : std::filesystem::path(options->csv);
    OutputPlan plan;
    plan.rewritten_input("FILE", options->path);  // /fits is added to it
    plan.output_file("--csv", csv);
    prepare_outputs(plan);
    const fit::FileFit fit = fit::fit_file(options->path, csv, models, fit_options,
                                           options->quadrature, options->threads, progress);
    reporter.finish();
    const fit::RadianceLobes& lobes = fit.lobes;
    fmt::print("scatterlab fit: {} ({} x {} spatial bins, {} x {} directions{})\n", options->path,
               lobes.r_bins(), lobes.z_bins(), fit.theta_bins, fit.phi_bins,
               lobes.phi_folded ? ", phi folded" : "");
    fmt::print("{}", fit::describe(fit::summarize(fit.run), fit.run));
    fmt::print("  wrote /fits/{{{}}} in {} and {}\n", options->models, options->path, csv.string());
    return 0;
  };
}

}  // namespace scatterlab::cli
