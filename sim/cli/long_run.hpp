#pragma once
// Checkpoints, --resume and interruption for any command that runs batches (simulate,
// searchlight, ...). A command registers the options with add_long_run_options, then runs each
// run through run_with_checkpoints (checkpointed_run.hpp), which makes the LongRun, passes
// long_run.control() to the transport, writes the file at result_path and calls finish().

#include <CLI/CLI.hpp>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "scatterlab/transport/communicator.hpp"
#include "scatterlab/transport/run_control.hpp"

namespace scatterlab::cli {

struct LongRunOptions {
  std::string checkpoint;  // path; default "<out>.checkpoint"
  std::string interval;    // "600", "600s", "10m", "2h" or "8b" (batches)
  bool resume = false;
};

// --checkpoint PATH, --checkpoint-interval INTERVAL, --resume
std::shared_ptr<LongRunOptions> add_long_run_options(CLI::App& command);

// --checkpoint, or OUT.checkpoint beside the output when it is not given.
std::filesystem::path checkpoint_path(const LongRunOptions& options,
                                      const std::filesystem::path& output);

// "600", "600s", "10m", "2h": seconds; "8b": batches. Throws InputError naming
// --checkpoint-interval.
CheckpointPolicy parse_checkpoint_interval(const std::string& text);

// Whether `output` is a complete scatterlab file of the run with this fingerprint: a run of a
// sweep or of an MCML file that is done already (a file that is not ours is not).
bool complete_file_of(const std::filesystem::path& output, const std::string& fingerprint);

// "run.partial.h5" for "run.h5": where a run stopped early writes its partial result when a
// complete file holds the output's name.
std::filesystem::path partial_sibling(const std::filesystem::path& output);

class LongRun {
 public:
  // Reads the checkpoint on the root when resuming (every rank learns whether that failed, so
  // that an error stops all of them) and catches SIGINT, SIGTERM and SIGUSR1 (which mpirun
  // forwards) until destroyed: the run then stops within about a second, abandoning the batches
  // it had not finished, and keeps the whole rounds folded before them.
  LongRun(const LongRunOptions& options, const std::filesystem::path& output,
          std::string fingerprint, Communicator& world);
  LongRun(const LongRun&) = delete;
  LongRun& operator=(const LongRun&) = delete;
  ~LongRun();

  const RunControl& control() const { return control_; }
  const std::filesystem::path& checkpoint_path() const { return checkpoint_path_; }
  // Batches already done by the run being resumed (0 when starting afresh).
  std::uint64_t resumed_batches() const { return state_ ? state_->batches_folded : 0; }

  // Where the file of a run that ran `batches_done` of `batches` goes. A complete run writes
  // `output`. A run stopped early never replaces a complete file (or any file that is not a
  // partial result): it then writes partial_sibling(output) instead, or, when that name is taken
  // by such a file too, no file at all (nullopt): the checkpoint holds the run. A run stopped
  // before two batches were folded writes no file either (one batch has no standard error).
  std::optional<std::filesystem::path> result_path(std::uint64_t batches_done,
                                                   std::uint64_t batches,
                                                   const std::filesystem::path& output) const;

  // After the file is written (to `written`, from result_path): for a complete run removes its
  // own checkpoint and partial sibling and returns 0; for a run stopped early prints what it
  // wrote and how to continue (root only) and returns 130.
  int finish(std::uint64_t batches_done, std::uint64_t batches, const std::filesystem::path& output,
             const std::optional<std::filesystem::path>& written) const;

 private:
  void remove_own_leftovers(const std::filesystem::path& output) const;

  Communicator& world_;
  std::filesystem::path checkpoint_path_;
  std::string fingerprint_;
  std::optional<RunState> state_;
  RunControl control_;
};

}  // namespace scatterlab::cli
