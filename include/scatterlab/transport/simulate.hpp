#pragma once
// Runs a validated SimulationSpec: photons in independent batches spread over threads, with
// batch statistics for every tally.

#include <cstdint>
#include <functional>
#include <vector>

#include "scatterlab/tally/tally_result.hpp"
#include "scatterlab/transport/simulation.hpp"

namespace scatterlab {

struct SimulationOutput {
  std::vector<TallyResult> tallies;
  double wall_seconds = 0.0;
  std::uint64_t photons = 0;
  std::uint64_t scattering_events = 0;
  int threads = 1;
};

// Called on the calling thread with the fraction of batches done, in [0, 1].
using ProgressCallback = std::function<void(double fraction_done)>;

// Results are bitwise identical for any thread count: each photon's random stream depends only
// on (seed, photon index), each batch is transported by one thread in photon order, and batches
// are folded into the statistics in batch order.
SimulationOutput simulate(const SimulationSpec& spec, const ProgressCallback& progress = {});

}  // namespace scatterlab
