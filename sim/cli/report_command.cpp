#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "log_interval_option.hpp"
#include "memory_limit_option.hpp"
#include "prepare_outputs.hpp"
#include "progress_reporter.hpp"
#include "run_options.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/io/plot.hpp"
#include "scatterlab/report/report_writer.hpp"
#include "scatterlab/report/suites.hpp"

namespace scatterlab::cli {
namespace {

struct ReportOptions {
  bool quick = false;
  std::vector<std::string> sections;  // empty: all
  std::string out = "scatterlab-report";
  report::Profile profile;
};

}  // namespace

Action add_report_command(CLI::App& app, const std::string& command_line) {
  auto* command = app.add_subcommand("report", kReportDescription);
  auto options = std::make_shared<ReportOptions>();
  command->add_flag("--quick", options->quick, "Small budgets, for the test suite (minutes)");
  command->add_option("-o,--out", options->out,
                      "Directory to write: new, empty or one scatterlab wrote (made if missing)");
  command->add_option("--threads", options->profile.threads, threads_help());
  add_memory_limit_option(*command);
  const auto log_interval = add_log_interval_option(*command);
  command->add_option(
      "--seed", options->profile.seed,
      "Seed of the first run (the next runs take the next seeds), in [0, 2^63 - 2^20]");

  // Each section by its id (its CSV stem), in the order of the report.
  using Suite = std::function<report::Section(const report::Profile&)>;
  const auto suites = std::make_shared<std::vector<std::pair<std::string, Suite>>>(
      std::vector<std::pair<std::string, Suite>> {
        {"infinite_medium_convergence", report::infinite_medium_convergence},
            {"infinite_medium_extremes", report::infinite_medium_extremes},
            {"half_space_convergence", report::half_space_convergence},
            {"half_space_extremes", report::half_space_extremes},
            {"sphere_convergence", report::sphere_convergence},
            {"sphere_extremes", report::sphere_extremes},
            {"slab_convergence", report::slab_convergence},
            {"slab_extremes", report::slab_extremes},
#if SCATTERLAB_WITH_RENDER
            {"mesh_convergence", report::mesh_convergence},
            {"mesh_tessellation", report::mesh_tessellation},
            {"mesh_extremes", report::mesh_extremes},
            {"volumetric_renderer_convergence", report::volumetric_renderer_convergence},
            {"volumetric_renderer_extremes", report::volumetric_renderer_extremes},
#endif
            {"lit_sphere_bssrdf_convergence", report::lit_sphere_bssrdf_convergence},
            {"lit_sphere_bssrdf_extremes", report::lit_sphere_bssrdf_extremes},
            {"half_space_models", report::half_space_model_accuracy},
            {"model_continua", report::model_continua}, {"lobe_fits", report::lobe_fit_accuracy}, {
          "refractive_solver", report::refractive_solver_accuracy
        }
      });
  std::string names;
  for (const auto& [name, suite] : *suites) names += (names.empty() ? "" : ", ") + name;
  command
      ->add_option("--section", options->sections,
                   "Run only these sections (repeat, or a comma-separated list): " + names)
      ->delimiter(',');

  return [options, command_line, suites, names, log_interval] {
    options->profile.quick = options->quick;
    check_threads(options->profile.threads, "--threads");
    // The sections run seeds from --seed upward (one per batch or cell), far fewer than 2^20.
    check_seed(options->profile.seed, "--seed", std::uint64_t{1} << 20);
    for (const std::string& wanted : options->sections) {
      bool known = false;
      for (const auto& entry : *suites) known |= entry.first == wanted;
      if (!known) throw InputError("--section", "got \"" + wanted + "\"", "one of " + names);
    }
    OutputPlan plan;
    plan.output_directory("--out", options->out);
    prepare_outputs(plan);
    require_plotting();  // before the sections, not after them
    plan.make_output_directories();
    auto chosen = [&options](const std::string& name) {
      return options->sections.empty() ||
             std::find(options->sections.begin(), options->sections.end(), name) !=
                 options->sections.end();
    };
    const auto to_run = static_cast<std::uint64_t>(
        std::count_if(suites->begin(), suites->end(),
                      [&chosen](const auto& entry) { return chosen(entry.first); }));
    ProgressReporter reporter("report", "sections", *log_interval);
    reporter.start(0, to_run);
    std::vector<report::Section> sections;
    int failed = 0;
    for (const auto& [name, suite] : *suites) {
      if (!chosen(name)) continue;
      sections.push_back(suite(options->profile));
      reporter.finish();  // the bar goes before the section's line on standard output
      const report::Section& section = sections.back();
      fmt::print("{:<55} {}\n", section.title, section.passed() ? "pass" : "FAIL");
      for (const std::string& failure : section.failures()) fmt::print("    {}\n", failure);
      std::fflush(stdout);
      failed += !section.passed();
      reporter.update(sections.size(), to_run);
    }
    reporter.finish();
    for (const auto& path : report::write_report(options->out, command_line, sections)) {
      fmt::print("wrote {}\n", path.string());
    }
    fmt::print("{} of {} sections pass; report in {}/report.md\n", sections.size() - failed,
               sections.size(), options->out);
    return failed == 0 ? 0 : 1;
  };
}

}  // namespace scatterlab::cli
