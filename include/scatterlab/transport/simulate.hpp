#pragma once
// Runs a validated SimulationSpec: photons in independent batches spread over threads, with
// batch statistics for every tally.

#include <cstdint>
#include <vector>

#include "scatterlab/tally/tally_result.hpp"
#include "scatterlab/transport/batch_runner.hpp"
#include "scatterlab/transport/simulation.hpp"

namespace scatterlab {

struct SimulationOutput {
  std::vector<TallyResult> tallies;  // on the root rank; empty on the others
  double wall_seconds = 0.0;
  std::uint64_t photons = 0;          // in the batches done
  std::uint64_t batches_done = 0;     // spec.run.batches unless stopped early
  std::uint64_t scattering_events = 0;
  int threads = 1;                    // per rank
  int ranks = 1;

  bool complete(const SimulationSpec& spec) const { return batches_done == spec.run.batches; }
};

// Bitwise identical for any thread and rank count, and when resumed (see batch_runner.hpp).
SimulationOutput simulate(const SimulationSpec& spec, const ProgressCallback& progress = {},
                          const RunControl& control = {});

}  // namespace scatterlab
