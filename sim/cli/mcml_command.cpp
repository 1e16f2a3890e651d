// scatterlab mcml FILE.mci: every run of an MCML input file (io/mcml_input.hpp) on the layered
// slab (transport/layered_slab.hpp), each written as our HDF5 file named after the run's output
// file (sample.mco -> sample.h5) in --out-dir (the current directory by default), or at --out
// for a file of one run, and, with --mco, as MCML's own .mco (io/mco_file.hpp) beside it. Every
// run is read, checked and planned before the first starts.
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "checkpointed_run.hpp"
#include "commands.hpp"
#include "log_interval_option.hpp"
#include "memory_limit_option.hpp"
#include "prepare_outputs.hpp"
#include "run_figures.hpp"
#include "run_options.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/io/mcml_input.hpp"
#include "scatterlab/io/mco_file.hpp"
#include "scatterlab/io/output_plan.hpp"
#include "scatterlab/io/simulation_file.hpp"
#include "scatterlab/transport/layered_slab.hpp"

namespace scatterlab::cli {
namespace {

struct McmlFlags {
  std::string input;
  std::string out, out_dir;  // out_dir empty: the current directory
  bool mco = false;
  std::string weighting = "analog";
  RunOptions run;
};

// The run of an .mci as our spec, the command's flags laid over its run settings.
LayeredSlabSpec slab_spec(const McmlRun& run, const CLI::App& command, const McmlFlags& flags) {
  LayeredSlabSpec spec = layered_slab_spec(run);
  spec.weighting = flags.weighting == "implicit" ? Weighting::implicit_capture : Weighting::analog;
  apply_run_options(command, flags.run, spec.run);
  spec.validate();
  return spec;
}

void print_summary(std::size_t index, std::size_t runs, const LayeredSlabSpec& spec,
                   const TransportOutput& out) {
  fmt::print("scatterlab mcml: run {} of {}: {} layers, {} weighting\n", index + 1, runs,
             spec.layers.size(), to_string(spec.weighting));
  print_run_time(out);
  print_energy_balance(out, slab_energy_tallies);
}

int run_mcml(const CLI::App& command, const McmlFlags& flags, const LongRunOptions& long_run,
             double log_interval, const std::string& command_line, World& world) {
  const std::vector<McmlRun> runs = read_mcml_input(flags.input);
  if (runs.size() > 1 && !long_run.checkpoint.empty()) {
    throw InputError(
        "--checkpoint",
        fmt::format("given for {} runs: every run checkpoints beside its file", runs.size()),
        "--checkpoint only for a file of one run");
  }
  OutputPlan plan;
  plan.input("FILE", flags.input);
  if (runs.size() > 1 && !flags.out.empty()) {
    throw InputError("--out", fmt::format("given for {} runs", runs.size()),
                     "--out only for a file of one run; --out-dir for the directory of them all");
  }
  std::vector<LayeredSlabSpec> specs;
  std::vector<std::filesystem::path> h5_paths, mco_paths;
  for (const McmlRun& run : runs) {
    specs.push_back(slab_spec(run, command, flags));
    check_transport_memory(transport_problem(specs.back()), world.size(), long_run.resume);
    // In --out-dir, whatever directory the .mci names its output in.
    const std::filesystem::path name =
        std::filesystem::path(flags.out_dir) / std::filesystem::path(run.output_file).filename();
    const std::string field = !flags.out.empty() ? "--out"
                              : command.get_option("--out-dir")->count() > 0
                                  ? "--out-dir"
                                  : fmt::format("{}:{} output file", flags.input, run.line);
    h5_paths.push_back(flags.out.empty() ? std::filesystem::path(name).replace_extension(".h5")
                                         : std::filesystem::path(flags.out));
    plan.output_file(field, h5_paths.back());
    plan.output_file("--checkpoint", checkpoint_path(long_run, h5_paths.back()));
    if (flags.mco) {
      mco_paths.push_back(
          flags.out.empty() ? name : std::filesystem::path(flags.out).replace_extension(".mco"));
      plan.output_file(field, mco_paths.back());
    }
  }
  prepare_outputs(plan, world.is_root());

  // Checkpoints, --resume and interruption as for every run (checkpointed_run.hpp): a run stopped
  // early keeps what it did in a partial file and its checkpoint, no .mco is written for it, and
  // the later runs wait; with --resume the runs whose files are complete are skipped.
  for (std::size_t i = 0; i < runs.size(); ++i) {
    LayeredSlabSpec& spec = specs[i];
    const bool done =
        long_run.resume && world.communicator().broadcast_from_root(
                               complete_file_of(h5_paths[i], fingerprint(spec)) ? 1 : 0) != 0;
    if (done) {
      if (world.is_root()) fmt::print("skip {}: done already\n", h5_paths[i].string());
      continue;
    }
    const int status = run_with_checkpoints(
        "mcml", long_run, h5_paths[i], fingerprint(spec), spec.run.batches, log_interval, world,
        [&spec](const ProgressCallback& progress, const RunControl& control) {
          return run_layered_slab(spec, progress, control);
        },
        [&](const std::filesystem::path& path, const TransportOutput& out) {
          spec.run.threads = out.threads;  // record what ran, not "all cores"
          write_simulation_file(path, spec, out.tallies, run_provenance(out, command_line));
          print_summary(i, runs.size(), spec, out);
          fmt::print("  wrote {}\n", path.string());
          if (!flags.mco || !out.complete(spec)) return;
          McmlRun as_run = runs[i];
          as_run.photons = out.photons;  // --photons may have changed the file's count
          write_mco(mco_paths[i], as_run, mco_results(out.tallies, as_run), out.run_wall_seconds());
          fmt::print("  wrote {} (MCML 1.2.2 layout)\n", mco_paths[i].string());
        });
    if (status != 0) return status;
  }
  return 0;
}

}  // namespace

Action add_mcml_command(CLI::App& app, const std::string& command_line, World& world) {
  auto* command = app.add_subcommand(
      "mcml",
      "Run every run of an MCML input file (.mci) on the layered slab: one HDF5 file per run, "
      "named after the run's output file (sample.mco -> sample.h5), in --out-dir; or --out for "
      "a file of one run");
  auto flags = std::make_shared<McmlFlags>();
  command->add_option("FILE", flags->input, "MCML 1.2.2 input file (.mci)")->required();
  CLI::Option* out =
      command->add_option("-o,--out", flags->out,
                          "The HDF5 file of a file of one run (the .mco beside it, as NAME.mco)");
  command
      ->add_option("--out-dir", flags->out_dir,
                   "Directory of the runs' files, each named after its run's output file; must "
                   "exist")
      ->excludes(out)
      ->default_str("the current directory");
  command->add_flag("--mco", flags->mco,
                    "Also write MCML's .mco text output, under the run's output file name (with "
                    "--out: NAME.mco beside it)");
  command
      ->add_option("--weighting", flags->weighting,
                   "analog: each photon is absorbed whole (energy balances photon by photon); "
                   "implicit: MCML's implicit capture with roulette")
      ->check(CLI::IsMember({"analog", "implicit"}));
  flags->run = run_options_of(LayeredSlabSpec{}.run);
  add_run_options(*command, flags->run);
  command->get_option("--photons")->default_str("the run's photon count");
  const auto long_run = add_long_run_options(*command);
  const auto log_interval = add_log_interval_option(*command);
  add_memory_limit_option(*command);
  return [command, flags, long_run, log_interval, command_line, &world] {
    return run_mcml(*command, *flags, *long_run, *log_interval, command_line, world);
  };
}

}  // namespace scatterlab::cli
