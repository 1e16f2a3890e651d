#pragma once
// Runs a validated InfiniteMediumSpec on the transport engine: the infinite medium, its tallies
// declared once (simulate.cpp), photons in independent batches spread over threads and ranks.

#include "scatterlab/transport/engine.hpp"
#include "scatterlab/transport/simulation.hpp"

namespace scatterlab {

// The engine's problem for this spec: geometry, source, declared tallies and run.
TransportProblem transport_problem(const InfiniteMediumSpec& spec);

// Bitwise identical for any thread and rank count, and when resumed (see batch_runner.hpp).
TransportOutput run_infinite_medium(const InfiniteMediumSpec& spec,
                                    const ProgressCallback& progress = {},
                                    const RunControl& control = {});

}  // namespace scatterlab
