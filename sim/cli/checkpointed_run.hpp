#pragma once
// One transport run of a command, as every command runs it (long_run.hpp): resumed from its
// checkpoint when asked, and said so; progress on standard error from the root; stopped within
// about a second on a signal; then, on the root, its file written where LongRun::result_path puts
// it (the output, or its partial sibling when stopped early). Returns LongRun::finish's status.
//
//   return run_with_checkpoints("simulate", options, output, fingerprint(spec), spec.run.batches,
//       log_interval, world,
//       [&](const ProgressCallback& progress, const RunControl& control) {
//         return run_infinite_medium(spec, progress, control); },
//       [&](const std::filesystem::path& path, const TransportOutput& out) { ... write ... });

#include <fmt/format.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "long_run.hpp"
#include "progress_reporter.hpp"
#include "scatterlab/parallel/world.hpp"
#include "scatterlab/transport/engine.hpp"

namespace scatterlab::cli {

template <class Run, class Write>
int run_with_checkpoints(const std::string& command, const LongRunOptions& options,
                         const std::filesystem::path& output, const std::string& fingerprint,
                         std::uint64_t batches, double log_interval, World& world, Run&& run,
                         Write&& write) {
  const bool root = world.is_root();
  LongRun long_run(options, output, fingerprint, world.communicator());
  if (root && long_run.resumed_batches() > 0) {
    fmt::print("scatterlab {}: resuming after batch {} of {} from {}\n", command,
               long_run.resumed_batches(), batches, long_run.checkpoint_path().string());
  }
  ProgressReporter reporter(command, "batches", log_interval);
  ProgressCallback progress;
  if (root) {
    reporter.start(long_run.resumed_batches(), batches);
    progress = [&reporter](const BatchProgress& done) { reporter.update(done); };
  }
  const TransportOutput out = run(progress, long_run.control());
  reporter.finish();

  std::optional<std::filesystem::path> written;
  if (root) {
    written = long_run.result_path(out.batches_done, batches, output);
    if (written) write(*written, out);
  }
  return long_run.finish(out.batches_done, batches, output, written);
}

}  // namespace scatterlab::cli
