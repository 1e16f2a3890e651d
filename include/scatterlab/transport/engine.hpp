#pragma once
// The transport engine: runs a TransportProblem in batches over threads and ranks
// (batch_runner.hpp) with the one random walk specialised for its geometry, phase function and
// estimator (random_walk.hpp), and finishes its declared tallies (tally_book.hpp).

#include <cstdint>
#include <vector>

#include "scatterlab/core/memory_budget.hpp"
#include "scatterlab/tally/tally_result.hpp"
#include "scatterlab/transport/batch_runner.hpp"
#include "scatterlab/transport/transport_problem.hpp"

namespace scatterlab {

struct TransportOutput {
  std::vector<TallyResult> tallies;  // on the root rank; empty on the others
  double wall_seconds = 0.0;         // of this process
  // This process's time in the random walk, summed over threads, and its events there
  // (BatchOutcome): a small run spends most of its wall time on set-up, the batches' tallies and
  // finishing, which is not a cost per event.
  double walk_seconds = 0.0;
  std::uint64_t walk_events = 0;
  std::uint64_t photons = 0;  // in the batches done, by this process and any it resumed
  // Done by the run this process resumed from a checkpoint (0 when it started afresh); the wall
  // time on the root rank only.
  std::uint64_t photons_resumed = 0;
  double resumed_wall_seconds = 0.0;
  std::uint64_t batches_done = 0;  // run.batches unless stopped early
  std::uint64_t scattering_events = 0;
  int threads = 1;        // per rank: what OpenMP granted
  int threads_asked = 1;  // per rank: what the run asked for (fewer when OpenMP withheld some)
  int ranks = 1;

  // The whole run's wall time, over every process that ran it.
  double run_wall_seconds() const { return resumed_wall_seconds + wall_seconds; }
  std::uint64_t session_photons() const { return photons - photons_resumed; }

  // Whether every batch of `spec` (anything with a RunSettings `run`) ran.
  template <class Spec>
  bool complete(const Spec& spec) const {
    return batches_done == spec.run.batches;
  }
};

// What transport() holds at its peak on the root rank: the batch runner's buffers for every
// tally value of the problem (batch_memory in batch_runner.hpp), the tally declarations and the
// finished tallies. `ranks` and `resuming` as the run will have them.
MemoryEstimate transport_memory(const TransportProblem& problem, int ranks, bool resuming);

// Throws InputError naming problem.size_fields and the figure when transport_memory does not fit
// in the memory limit (core/memory_budget.hpp). transport() checks this itself before it
// allocates; commands call it for every run they plan before any of them starts.
void check_transport_memory(const TransportProblem& problem, int ranks, bool resuming);

// At most how many events (collisions) a photon of `problem` takes on average, known before any
// photon runs. Each collision absorbs a fraction 1 - albedo of what reaches it (analog
// absorption), so a photon absorbed with probability A collides A / (1 - albedo) times on
// average: at most 1 / (1 - albedo), reached in the infinite medium, whose escape radius bounds
// it too (run_settings.hpp, expected_events_per_photon). Infinite at albedo 1 without an escape
// radius. In a slab, an estimate: the bound at its layers' highest albedo (under implicit
// capture, the events until roulette ends the weight), at most the escape radius's, and for a
// stack of finite optical depth tau about 2.6 tau events, the time light that enters at its surface
// takes to leave it. 0 for a stack of clear layers.
double events_per_photon_bound(const TransportProblem& problem);

// The albedo that bounds those events: the medium's, or a slab's layers' highest.
double highest_albedo(const TransportProblem& problem);

// Bitwise identical for any thread and rank count, and when resumed (batch_runner.hpp).
// Throws std::invalid_argument for a problem no kernel runs (the track-length estimator in a
// geometry with a surface); specs validate their fields before they get here.
TransportOutput transport(const TransportProblem& problem, const ProgressCallback& progress = {},
                          const RunControl& control = {});

}  // namespace scatterlab
