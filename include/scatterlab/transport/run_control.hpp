#pragma once
// How a run is driven, as opposed to what it computes (run_settings.hpp): across processes,
// with periodic checkpoints, resumed from one, or stopped early on request. None of this changes
// a single bit of the result: a run split over ranks, resumed, or both, folds the same batches in
// the same order as one uninterrupted process.

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "scatterlab/transport/communicator.hpp"

namespace scatterlab {

// Everything needed to continue a run after `batches_folded` batches: the Welford state of
// every tally cell (batch_statistics.hpp), the scattering events counted so far and the wall
// time spent on them.
struct RunState {
  std::uint64_t batches_folded = 0;
  std::uint64_t scattering_events = 0;
  // Wall time spent on the run so far, over every process that ran it (a resumed run adds its
  // own), so that rates and figures of merit can count the whole run.
  double wall_seconds = 0.0;
  std::vector<double> mean;     // per photon, every cell
  std::vector<double> squares;  // Welford's running sum of squared deviations
};

// When to save the state. Either bound triggers a checkpoint once the group of batches that
// crosses it is folded; both zero means never.
struct CheckpointPolicy {
  double every_seconds = 0.0;
  std::uint64_t every_batches = 0;

  bool enabled() const { return every_seconds > 0.0 || every_batches > 0; }
};

struct RunControl {
  // Null: this process alone. Otherwise every rank calls the runner with the same arguments.
  Communicator* communicator = nullptr;

  // Called on the root rank with the whole state at each checkpoint (the runner gathers it),
  // and when stopped early. Set it on every rank or on none (other ranks' copies are not called).
  std::function<void(const RunState&)> save_checkpoint;
  CheckpointPolicy checkpoint;

  // Read on the root rank only: continue from this state instead of batch 0. The caller checks
  // that it belongs to the same run (same parameters and seed).
  const RunState* resume_from = nullptr;
  // Where resume_from was read (the checkpoint's path), for the error when it does not fit.
  std::string resume_source;

  // Polled every thousand photons or so within each batch, on every rank. Once any rank sees it
  // set, all ranks stop: the first group of batches with a batch cut short is abandoned
  // everywhere, and the outcome holds the whole groups before it.
  const std::atomic<bool>* stop_requested = nullptr;
};

}  // namespace scatterlab
