#include "long_run.hpp"

#include <fmt/format.h>
#include <signal.h>
#include <sys/types.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <exception>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/checkpoint_file.hpp"

namespace scatterlab::cli {
namespace {

constexpr double kDefaultIntervalSeconds = 600.0;
constexpr int kInterruptedExit = 130;  // 128 + SIGINT, as shells report it

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

// A run killed while writing a checkpoint leaves "<checkpoint>.tmp-<pid>-<n>" behind
// (atomic_output.hpp); remove those whose process is gone.
void remove_stale_temporaries(const std::filesystem::path& checkpoint) {
  const std::string prefix = checkpoint.filename().string() + ".tmp-";
  const std::filesystem::path directory =
      checkpoint.has_parent_path() ? checkpoint.parent_path() : std::filesystem::path(".");
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(directory, error)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
    if (pid > 0 && ::kill(static_cast<pid_t>(pid), 0) == -1 && errno == ESRCH) {
      std::filesystem::remove(entry.path(), error);
    }
  }
}

}  // namespace

std::shared_ptr<LongRunOptions> add_long_run_options(CLI::App& command) {
  auto options = std::make_shared<LongRunOptions>();
  command.add_option("--checkpoint", options->checkpoint,
                     "Save the run's state here periodically, atomically [OUT.checkpoint]");
  command.add_option("--checkpoint-interval", options->interval,
                     "Checkpoint every INTERVAL: seconds (600, 600s, 10m, 2h) or batches (8b); "
                     "checkpoints are off unless this, --checkpoint or --resume is given [10m]");
  command.add_flag("--resume", options->resume,
                   "Continue from the checkpoint if there is one (same parameters and seed); the "
                   "result equals an uninterrupted run, bit for bit");
  return options;
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

LongRun::LongRun(const LongRunOptions& options, const std::filesystem::path& output,
                 std::string fingerprint, Communicator& world)
    : world_(world),
      checkpoint_path_(options.checkpoint.empty() ? default_checkpoint_path(output)
                                                  : std::filesystem::path(options.checkpoint)),
      fingerprint_(std::move(fingerprint)) {
  if (!options.interval.empty()) {
    control_.checkpoint = parse_checkpoint_interval(options.interval);
  } else if (!options.checkpoint.empty() || options.resume) {
    control_.checkpoint.every_seconds = kDefaultIntervalSeconds;
  }
  // Resume on the root; every rank must learn whether it failed, or the others would wait for it.
  std::exception_ptr failure;
  if (options.resume && world.is_root()) {
    remove_stale_temporaries(checkpoint_path_);
    try {
      if (std::filesystem::exists(checkpoint_path_)) {
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

int LongRun::finish(std::uint64_t batches_done, std::uint64_t batches,
                    const std::filesystem::path& output) const {
  if (batches_done == batches) {
    std::error_code ignored;  // none was written when checkpoints were off and nothing stopped
    if (world_.is_root()) std::filesystem::remove(checkpoint_path_, ignored);
    return 0;
  }
  if (world_.is_root()) {
    fmt::print(stderr,
               "scatterlab: interrupted after {} of {} batches: wrote {} marked partial; "
               "rerun the same command with --resume to finish from {}\n",
               batches_done, batches, output.string(), checkpoint_path_.string());
  }
  return kInterruptedExit;
}

}  // namespace scatterlab::cli
