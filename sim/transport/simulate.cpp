#include "scatterlab/transport/simulate.hpp"

#include <chrono>

#include "scatterlab/core/phase_function.hpp"
#include "scatterlab/tally/scorer.hpp"
#include "scatterlab/transport/random_walk.hpp"

namespace scatterlab {
namespace {

SimulationOutput collect(const SimulationSpec& spec, const TallyLayout& layout,
                         const BatchOutcome& outcome) {
  SimulationOutput output;
  if (!outcome.mean.empty()) {
    output.tallies = finalize_tallies(spec, layout, outcome.mean, outcome.standard_error);
  }
  output.photons = outcome.photons_done;
  output.batches_done = outcome.batches_done;
  output.threads = outcome.threads;
  output.ranks = outcome.ranks;
  output.scattering_events = outcome.scattering_events;
  return output;
}

template <class Phase>
SimulationOutput simulate_with(const SimulationSpec& spec, const Phase& phase,
                               const ProgressCallback& progress, const RunControl& control) {
  const TallyLayout layout(spec);
  const Scorer scorer(spec, layout);
  if (spec.tallies.estimator == Estimator::collision) {
    const RandomWalk<Phase, Estimator::collision> walk(spec, phase, scorer);
    return collect(spec, layout, run_batches(spec.run, layout.size, walk, progress, control));
  }
  const RandomWalk<Phase, Estimator::track_length> walk(spec, phase, scorer);
  return collect(spec, layout, run_batches(spec.run, layout.size, walk, progress, control));
}

}  // namespace

SimulationOutput simulate(const SimulationSpec& spec, const ProgressCallback& progress,
                          const RunControl& control) {
  spec.validate();
  const auto start = std::chrono::steady_clock::now();
  // g = 0 samples isotropically: no HG arithmetic where the scene does not need it.
  SimulationOutput output = spec.medium.g == 0.0
                                ? simulate_with(spec, IsotropicPhase{}, progress, control)
                                : simulate_with(spec, HenyeyGreenstein{spec.medium.g}, progress, control);
  output.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return output;
}

}  // namespace scatterlab
