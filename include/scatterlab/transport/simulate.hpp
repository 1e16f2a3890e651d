#pragma once
// Runs a validated SimulationSpec on the transport engine: the infinite medium, its tallies
// declared once (simulate.cpp), photons in independent batches spread over threads and ranks.

#include "scatterlab/transport/engine.hpp"
#include "scatterlab/transport/simulation.hpp"

namespace scatterlab {

using SimulationOutput = TransportOutput;

// The engine's problem for this spec: geometry, source, declared tallies and run.
TransportProblem transport_problem(const SimulationSpec& spec);

// Bitwise identical for any thread and rank count, and when resumed (see batch_runner.hpp).
SimulationOutput simulate(const SimulationSpec& spec, const ProgressCallback& progress = {},
                          const RunControl& control = {});

}  // namespace scatterlab
