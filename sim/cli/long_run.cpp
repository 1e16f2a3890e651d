#include "long_run.hpp"

#include <fmt/format.h>
#include <signal.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <exception>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/checkpoint_file.hpp"
#include "scatterlab/io/simulation_file.hpp"

namespace scatterlab::cli {
namespace {

constexpr double kDefaultIntervalSeconds = 600.0;
constexpr int kInterruptedExit = 130;  // 128 + SIGINT, as shells report it
// A partial file needs two batches: one says nothing about the spread (its standard error would
// be NaN). A run stopped before then leaves only its checkpoint.
constexpr std::uint64_t kFewestPartialBatches = 2;

// Set from the signal handler: lock-free atomics are async-signal-safe.
std::atomic<bool> stop_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void request_stop(int) {
  stop_requested.store(true);
}

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGUSR1};

void catch_signals() {
  struct sigaction action {};
  action.sa_handler = request_stop;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;  // a second signal ends the process at once
  for (const int signal : kSignals) sigaction(signal, &action, nullptr);
}

void restore_signals() {
  for (const int signal : kSignals) std::signal(signal, SIG_DFL);
}

// A checkpoint path may hold only this run's own checkpoint: anything else there (notes, the
// output, another run's checkpoint) is not the run's to replace, nor to remove when it ends.
void refuse_foreign_checkpoint(const std::filesystem::path& checkpoint,
                               const std::string& fingerprint) {
  std::error_code error;
  if (!std::filesystem::exists(std::filesystem::symlink_status(checkpoint, error))) return;
  if (is_checkpoint_of(checkpoint, fingerprint)) return;
  throw InputError("--checkpoint",
                   fmt::format("'{}' exists and is not a checkpoint of this run (same "
                               "parameters and seed); it is left as it is",
                               checkpoint.string()),
                   "a path where no file is yet, or this run's own checkpoint (with --resume "
                   "to continue from it)");
}

}  // namespace

std::shared_ptr<LongRunOptions> add_long_run_options(CLI::App& command) {
  auto options = std::make_shared<LongRunOptions>();
  // Both defaults follow from other input (the output's name; whether checkpoints are on), so
  // the help shows what they come to rather than an empty value.
  command
      .add_option("--checkpoint", options->checkpoint,
                  "Save the run's state here periodically, atomically: a path where no file is "
                  "yet, or this run's own checkpoint, which is removed when the run completes; "
                  "any other file there stops the run before it starts")
      ->default_str("OUT.checkpoint");
  command
      .add_option("--checkpoint-interval", options->interval,
                  "Checkpoint every INTERVAL: seconds (600, 600s, 10m, 2h) or batches (8b); "
                  "checkpoints are off unless this, --checkpoint or --resume is given")
      ->default_str(fmt::format("{:g}s", kDefaultIntervalSeconds));
  command.add_flag("--resume", options->resume,
                   "Continue from the checkpoint if there is one (same parameters and seed); the "
                   "result equals an uninterrupted run, bit for bit. Interrupted (SIGINT, SIGTERM, "
                   "SIGUSR1), a run stops within about a second, dropping the batches it had not "
                   "finished, saves its checkpoint and writes OUT marked partial (when it holds "
                   "two batches or more), but never over a complete file: then it writes OUT's "
                   "name with .partial before the extension (run.partial.h5), removed when the "
                   "resumed run completes. A damaged checkpoint (numbers that are not finite, "
                   "negative squares, counts or sizes that do not fit the run) is refused");
  return options;
}

std::filesystem::path checkpoint_path(const LongRunOptions& options,
                                      const std::filesystem::path& output) {
  return options.checkpoint.empty() ? default_checkpoint_path(output)
                                    : std::filesystem::path(options.checkpoint);
}

CheckpointPolicy parse_checkpoint_interval(const std::string& text) {
  const auto bad = [&text]() {
    return InputError("--checkpoint-interval", fmt::format("got \"{}\"", text),
                      "a positive number of seconds (600, 600s, 10m, 2h) or of batches (8b)");
  };
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    throw bad();
  }
  const std::string unit = text.substr(used);
  if (!(value > 0.0) || !std::isfinite(value)) throw bad();
  CheckpointPolicy policy;
  if (unit.empty() || unit == "s") {
    policy.every_seconds = value;
  } else if (unit == "m") {
    policy.every_seconds = 60.0 * value;
  } else if (unit == "h") {
    policy.every_seconds = 3600.0 * value;
  } else if (unit == "b" && value == std::floor(value) && value < 0x1p63) {
    policy.every_batches = static_cast<std::uint64_t>(value);
  } else {
    throw bad();
  }
  return policy;
}

bool complete_file_of(const std::filesystem::path& output, const std::string& fingerprint) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(output, error)) return false;
  try {
    const FileSummary summary = read_file_header(output);
    return !summary.partial && summary.spec_fingerprint == fingerprint;
  } catch (const std::exception&) {
    return false;  // not a scatterlab file: replaced by the run
  }
}

LongRun::LongRun(const LongRunOptions& options, const std::filesystem::path& output,
                 std::string fingerprint, Communicator& world)
    : world_(world),
      checkpoint_path_(cli::checkpoint_path(options, output)),
      fingerprint_(std::move(fingerprint)) {
  if (!options.interval.empty()) {
    control_.checkpoint = parse_checkpoint_interval(options.interval);
  } else if (!options.checkpoint.empty() || options.resume) {
    control_.checkpoint.every_seconds = kDefaultIntervalSeconds;
  }
  // Resume on the root; every rank must learn whether it failed, or the others would wait for it.
  std::exception_ptr failure;
  if (world.is_root()) {
    try {
      if (!options.resume) {
        refuse_foreign_checkpoint(checkpoint_path_, fingerprint_);
      } else if (std::filesystem::exists(checkpoint_path_)) {
        state_ = read_checkpoint(checkpoint_path_, fingerprint_);
      } else {
        fmt::print(stderr, "scatterlab: no checkpoint at {}: starting from the first batch\n",
                   checkpoint_path_.string());
      }
    } catch (...) {
      failure = std::current_exception();
    }
  }
  if (world.broadcast_from_root(failure ? 1 : 0) != 0) {
    if (failure) std::rethrow_exception(failure);
    throw InputError("--resume", "the root rank could not read the checkpoint", "see rank 0");
  }
  if (state_) control_.resume_from = &*state_;
  control_.resume_source = checkpoint_path_.string();
  control_.communicator = &world;
  // The state is always saved when a run stops early, so that it can be resumed.
  control_.save_checkpoint = [this](const RunState& state) {
    write_checkpoint(checkpoint_path_, fingerprint_, state);
  };
  stop_requested.store(false);
  control_.stop_requested = &stop_requested;
  catch_signals();
}

LongRun::~LongRun() {
  restore_signals();
}

std::filesystem::path partial_sibling(const std::filesystem::path& output) {
  std::filesystem::path sibling = output;
  sibling.replace_extension();
  sibling += ".partial";
  sibling += output.extension();
  return sibling;
}

namespace {

// A partial result may take the place only of nothing or of another partial result.
bool holds_partial_or_nothing(const std::filesystem::path& path) {
  std::error_code error;
  if (!std::filesystem::exists(std::filesystem::symlink_status(path, error))) return true;
  try {
    return std::filesystem::is_regular_file(path, error) && read_file_header(path).partial;
  } catch (const std::exception&) {
    return false;  // not a scatterlab file
  }
}

}  // namespace

std::optional<std::filesystem::path> LongRun::result_path(
    std::uint64_t batches_done, std::uint64_t batches, const std::filesystem::path& output) const {
  if (batches_done == batches) return output;
  if (batches_done < kFewestPartialBatches) return std::nullopt;
  if (holds_partial_or_nothing(output)) return output;
  const std::filesystem::path sibling = partial_sibling(output);
  if (holds_partial_or_nothing(sibling)) return sibling;
  return std::nullopt;
}

int LongRun::finish(std::uint64_t batches_done, std::uint64_t batches,
                    const std::filesystem::path& output,
                    const std::optional<std::filesystem::path>& written) const {
  if (batches_done == batches) {
    if (world_.is_root()) remove_own_leftovers(output);
    return 0;
  }
  if (world_.is_root()) {
    if (batches_done == 0) {
      fmt::print(stderr,
                 "scatterlab: interrupted before the first batch was complete: wrote "
                 "no file and no checkpoint; rerun the same command to start again\n");
      return kInterruptedExit;
    }
    std::string what;
    if (batches_done < kFewestPartialBatches) {
      what = "too few for a standard error, so wrote no file";
    } else if (!written) {
      what = fmt::format("kept {} and {}, which are not partial results, and wrote no file",
                         output.string(), partial_sibling(output).string());
    } else if (*written != output) {
      what = fmt::format("kept {}, which is not a partial result, and wrote {} marked partial",
                         output.string(), written->string());
    } else {
      what = fmt::format("wrote {} marked partial", output.string());
    }
    fmt::print(stderr,
               "scatterlab: interrupted after {} of {} batches: {}; rerun the same command with "
               "--resume to finish from {}\n",
               batches_done, batches, what, checkpoint_path_.string());
  }
  return kInterruptedExit;
}

// What this run (or the run it resumed) left for itself: its checkpoint, and a partial result
// written beside a complete file; anything else at those paths is not the run's to remove.
void LongRun::remove_own_leftovers(const std::filesystem::path& output) const {
  std::error_code ignored;
  if (is_checkpoint_of(checkpoint_path_, fingerprint_)) {
    std::filesystem::remove(checkpoint_path_, ignored);
  }
  const std::filesystem::path sibling = partial_sibling(output);
  if (!std::filesystem::is_regular_file(sibling, ignored)) return;
  try {
    const FileSummary summary = read_file_header(sibling);
    if (summary.partial && summary.spec_fingerprint == fingerprint_) {
      std::filesystem::remove(sibling, ignored);
    }
  } catch (const std::exception&) {
    // not a scatterlab file: not ours
  }
}

}  // namespace scatterlab::cli
