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
  std::vector<TallyResult> tallies;
  double wall_seconds = 0.0;
  std::uint64_t photons = 0;
  std::uint64_t scattering_events = 0;
  int threads = 1;
};

// Bitwise identical for any thread count (see batch_runner.hpp).
SimulationOutput simulate(const SimulationSpec& spec, const ProgressCallback& progress = {});

}  // namespace scatterlab
