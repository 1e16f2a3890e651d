// scatterlab merge: independent runs of one scene (different seeds) pooled into one file.
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <vector>

#include "commands.hpp"
#include "memory_limit_option.hpp"
#include "prepare_outputs.hpp"
#include "scatterlab/io/merge.hpp"

namespace scatterlab::cli {

Action add_merge_command(CLI::App& app, const std::string& command_line) {
  auto* merge = app.add_subcommand(
      "merge",
      "Pool independent runs of the same scene (different seeds) into one file: every batch of "
      "every run counts once in the mean and the standard error; photons add up. Refuses runs "
      "that differ in anything but seed, photons, batches and threads; partial files (finish them "
      "with --resume first), files of another format_version, files whose batch and photon "
      "counts disagree, and tallies holding NaN or inf. Model curves (/models) are kept when "
      "every input holds the same ones, and otherwise left out, saying so on stderr.");
  struct Options {
    std::vector<std::string> inputs;
    std::string out;
  };
  auto o = std::make_shared<Options>();
  merge->add_option("FILES", o->inputs, "Two or more files written by scatterlab simulate")
      ->required()
      ->check(CLI::ExistingFile);
  merge->add_option("-o,--out", o->out, "Merged HDF5 file")->required();
  add_memory_limit_option(*merge);
  return [o, command_line] {
    const std::vector<std::filesystem::path> inputs(o->inputs.begin(), o->inputs.end());
    OutputPlan plan;
    for (const auto& input : inputs) plan.input("FILES", input);
    plan.output_file("--out", o->out);
    prepare_outputs(plan);
    const MergeSummary summary = merge_simulation_files(inputs, o->out, command_line);
    fmt::print("scatterlab merge: {} runs, {} photons in {} batches: wrote {}\n", inputs.size(),
               summary.photons, summary.batches, o->out);
    if (!summary.models_dropped.empty()) {
      fmt::print(stderr, "scatterlab merge: left out /models: {}\n", summary.models_dropped);
    }
    if (summary.unequal_batches) {
      fmt::print(
          "  note: the runs differ in photons per batch; every batch weighs the same in "
          "the merged mean (unbiased, as is its standard error, but not the least "
          "variance possible)\n");
    }
    return 0;
  };
}

}  // namespace scatterlab::cli
