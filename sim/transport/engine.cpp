#include "scatterlab/transport/engine.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "scatterlab/transport/half_space.hpp"
#include "scatterlab/transport/infinite_medium.hpp"
#include "scatterlab/transport/kernel.hpp"
#include "scatterlab/transport/run_settings.hpp"
#include "scatterlab/transport/slab.hpp"
#include "scatterlab/transport/sphere.hpp"

namespace scatterlab {
namespace {

// The slab's layers hold their own media (the phase function is unused) and are scored at events
// alone.
BatchOutcome run_slab(const detail::Kernel& kernel) {
  const TransportProblem& problem = kernel.problem;
  if (kernel.book.scores_volume()) {
    throw std::invalid_argument("transport: a slab is scored at absorption and exit only");
  }
  const Slab geometry(problem.layers, problem.n_above, problem.n_below);
  if (problem.weighting == Weighting::implicit_capture) {
    return kernel.run<Slab, IsotropicPhase, Estimator::none, Weighting::implicit_capture>(
        geometry, IsotropicPhase{}, problem.source);
  }
  return kernel.run<Slab, IsotropicPhase, Estimator::none>(geometry, IsotropicPhase{},
                                                                 problem.source);
}

// The geometries this module holds. eta = 1: no Fresnel arithmetic and no extra random numbers
// at the surface.
BatchOutcome select_kernel(const detail::Kernel& kernel) {
  const TransportProblem& problem = kernel.problem;
  if (problem.weighting != Weighting::analog && problem.geometry != GeometryKind::slab) {
    throw std::invalid_argument("transport: implicit capture runs only in a slab");
  }
  const Source& source = problem.source;
  switch (problem.geometry) {
    case GeometryKind::infinite:
      return kernel.with_phase(InfiniteMedium{}, source);
    case GeometryKind::half_space:
      if (problem.eta == 1.0) return kernel.with_phase(HalfSpace<false>(problem.eta), source);
      return kernel.with_phase(HalfSpace<true>(problem.eta), source);
    case GeometryKind::sphere:
      if (problem.eta == 1.0) return kernel.with_phase(Sphere<false>(problem.radius, 1.0), source);
      return kernel.with_phase(Sphere<true>(problem.radius, problem.eta), source);
    case GeometryKind::slab:
      return run_slab(kernel);
    case GeometryKind::mesh:
      throw std::invalid_argument(
          "transport: a mesh runs with its geometry and light (kernel.hpp, mesh/lit_mesh.hpp)");
  }
  throw std::invalid_argument("transport: unknown geometry");
}

}  // namespace

MemoryEstimate transport_memory(const TransportProblem& problem, int ranks, bool resuming) {
  const TallyBook book(problem.tallies, problem.split_by_order);
  MemoryEstimate need =
      batch_memory(book.size(), batch_threads(problem.run), problem.run.batches, ranks, resuming);
  // The declarations' bin measures, held by the problem and by the book.
  std::uint64_t measures = 0;
  for (const TallyDeclaration& d : problem.tallies) {
    for (const Filter& f : d.filters) measures += f.bins();
  }
  need.add_doubles("copies of the bin measures", measures, 2);
  // The track-length estimator's crossings, per thread (Scorer::make_crossing_scratch).
  if (problem.estimator == Estimator::track_length && book.scores_volume()) {
    const TallyAxes& a = problem.axes;
    const auto crossings =
        static_cast<std::uint64_t>(2 * a.r.bins + a.z.bins + a.phi.bins + 2 * a.rho.bins + 8);
    need.add_doubles("crossing lists (one per thread)", crossings,
                     static_cast<std::uint64_t>(batch_threads(problem.run)));
  }
  // Specs, names, shapes and the scorer's tables: small, whatever the grid.
  need.add("the run's small state", std::uint64_t{1} << 20);
  return need;
}

void check_transport_memory(const TransportProblem& problem, int ranks, bool resuming) {
  check_memory(transport_memory(problem, ranks, resuming), problem.size_fields,
               "fewer bins or tallies, or fewer threads");
}

namespace {

// The slab's bound (engine.hpp): its layers' highest albedo and densest medium, the escape
// radius in that medium's mfp, and, where every layer is finite, the time a random walk takes to
// leave the stack.
double slab_events_per_photon_bound(const TransportProblem& problem) {
  double sigma_t = 0.0, depth = 0.0;
  for (const SlabLayer& layer : problem.layers) {
    sigma_t = std::max(sigma_t, layer.sigma_t);
    depth += layer.sigma_t * layer.thickness;  // inf for a semi-infinite last layer
  }
  if (sigma_t == 0.0) return 0.0;  // clear layers only: no events
  const double albedo = highest_albedo(problem);
  double bound = expected_events_per_photon(albedo, problem.run.escape_radius * sigma_t);
  if (problem.weighting == Weighting::implicit_capture && albedo > 0.0 && albedo < 1.0) {
    // Each event leaves the weight times the albedo, at most: the first roulette comes after
    // ln(threshold) / ln(albedo) events, and each survivor (1 in 1 / roulette_chance) needs
    // ln(1 / roulette_chance) / -ln(albedo) more to meet the next.
    const double per_factor = -1.0 / std::log(albedo);  // events per factor e of weight
    const double roulettes = roulette_chance / (1.0 - roulette_chance);
    bound = std::min(
        bound, (std::log(1.0 / roulette_threshold) + roulettes * std::log(1.0 / roulette_chance)) *
                   per_factor);
  }
  // Light entering at the surface of a stack of optical depth tau leaves it after about
  // 2.6 tau events, whatever g: a diffusion of D = l l* / 3 per event (l the mfp, l* the
  // transport mfp) between extrapolated boundaries 0.71 l* outside each face, started l* deep,
  // leaves after (x0 + z_b) L / 2D = 1.71 l* L / (2 l l* / 3) = 2.57 L / l events (the mean exit
  // time x (L - x) / 2D of a diffusion). Measured on one conservative layer of tau 10, 100, 1000
  // and g 0, 0.9: 2.4 to 2.8 tau.
  return std::min(bound, 1.0 + 2.6 * depth);
}

}  // namespace

double highest_albedo(const TransportProblem& problem) {
  if (problem.geometry != GeometryKind::slab) return problem.albedo;
  double highest = 0.0;
  for (const SlabLayer& layer : problem.layers) {
    if (layer.sigma_t > 0.0) highest = std::max(highest, layer.albedo);  // a clear layer: none
  }
  return highest;
}

double events_per_photon_bound(const TransportProblem& problem) {
  if (problem.geometry == GeometryKind::slab) return slab_events_per_photon_bound(problem);
  return expected_events_per_photon(problem.albedo, problem.run.escape_radius);
}

TransportOutput transport(const TransportProblem& problem, const ProgressCallback& progress,
                          const RunControl& control) {
  return detail::run_kernel(problem, progress, control, select_kernel);
}

TransportOutput detail::run_kernel(const TransportProblem& problem,
                                   const ProgressCallback& progress, const RunControl& control,
                                   const std::function<BatchOutcome(const Kernel&)>& select) {
  const auto start = std::chrono::steady_clock::now();
  // Every rank decides on the root's figure (it alone holds a resumed state), so that all stop.
  SerialCommunicator serial;
  Communicator& world = control.communicator != nullptr ? *control.communicator : serial;
  const bool resuming = world.broadcast_from_root(control.resume_from != nullptr ? 1 : 0) != 0;
  check_transport_memory(problem, world.size(), resuming);
  const TallyBook book(problem.tallies, problem.split_by_order);
  const Scorer scorer(problem.axes, book);
  const BatchOutcome outcome = select(Kernel{problem, book, scorer, progress, control});
  TransportOutput output;
  if (!outcome.mean.empty()) {  // the root's; other ranks fold only their slice
    output.tallies =
        book.finish(outcome.mean, outcome.standard_error, problem.photon_power, problem.length);
  }
  output.photons = outcome.photons_done;
  output.photons_resumed = outcome.photons_resumed;
  output.resumed_wall_seconds = outcome.resumed_wall_seconds;
  output.walk_seconds = outcome.walk_seconds;
  output.walk_events = outcome.walk_events;
  output.batches_done = outcome.batches_done;
  output.threads = outcome.threads;
  output.threads_asked = outcome.threads_asked;
  output.ranks = outcome.ranks;
  output.scattering_events = outcome.scattering_events;
  output.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return output;
}

}  // namespace scatterlab
