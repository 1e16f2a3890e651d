#pragma once
// The engine's kernel selection (engine.hpp), open to geometries the transport module does not
// hold: a triangle mesh traced with Embree (mesh/mesh_boundary.hpp) brings its geometry and its
// light and runs on the same random walk, batches, statistics and tallies as every other scene.
//
// A geometry is a policy of random_walk.hpp; a light provides
//   bool launch(PhotonRandom&, Vec3& start, Vec3& heading) const;
// as Source (source.hpp) does: false when the photon is reflected off the surface and never
// enters.

#include <functional>
#include <optional>
#include <stdexcept>
#include <type_traits>

#include "scatterlab/core/phase_function.hpp"
#include "scatterlab/tally/scorer.hpp"
#include "scatterlab/tally/tally_book.hpp"
#include "scatterlab/transport/batch_runner.hpp"
#include "scatterlab/transport/engine.hpp"
#include "scatterlab/transport/half_space.hpp"
#include "scatterlab/transport/infinite_medium.hpp"
#include "scatterlab/transport/lane_walk.hpp"
#include "scatterlab/transport/random_walk.hpp"
#include "scatterlab/transport/slab.hpp"
#include "scatterlab/transport/sphere.hpp"

namespace scatterlab {
namespace detail {

// What every kernel shares: the problem, its tallies' buffer layout and scorer, and how to run.
struct Kernel {
  const TransportProblem& problem;
  const TallyBook& book;
  const Scorer& scorer;
  const ProgressCallback& progress;
  const RunControl& control;

  // The infinite medium's, the half-space's, the sphere's, the slab's and a convex object's
  // photons share vector lanes (lane_walk.hpp): an object when its module gives it and its light
  // as an ObjectBoundary (object_boundary(geometry, light), found by argument-dependent lookup).
  // The track-length estimator and other objects keep RandomWalk.
  template <class Geometry, class Phase, Estimator estimator,
            Weighting weighting = Weighting::analog, class Light = Source>
  BatchOutcome run(const Geometry& geometry, const Phase& phase, const Light& light) const {
    // Chained tallies (time of flight among them) bin each event by its filters: the one walk
    // that keeps each photon's path.
    if (book.has_chain()) {
      if constexpr (estimator == Estimator::track_length) {
        throw std::invalid_argument("transport: chained tallies take the collision estimator");
      } else {
        const RandomWalk<Geometry, Phase, estimator, weighting, Light, true> walk(
            geometry, phase, light, scorer, problem.albedo, problem.run.escape_radius,
            problem.run.seed);
        return run_batches(problem.run, book.size(), walk, progress, control);
      }
    }
    if constexpr (requires { object_boundary(geometry, light); } &&
                  weighting == Weighting::analog && estimator != Estimator::track_length) {
      if (const std::optional<ObjectBoundary> object = object_boundary(geometry, light)) {
        const LaneWalk walk(*object, scorer, problem.albedo, phase.mean_cosine(), estimator,
                            problem.run.escape_radius, problem.run.seed);
        return run_batches(problem.run, book.size(), walk, progress, control);
      }
    }
    if constexpr (std::is_same_v<Light, Source> && std::is_same_v<Geometry, Slab>) {
      const LaneWalk walk(geometry, weighting, scorer, light, problem.run.escape_radius,
                          problem.run.seed);
      return run_batches(problem.run, book.size(), walk, progress, control);
    } else if constexpr (std::is_same_v<Light, Source> && is_lane_geometry<Geometry> &&
                         weighting == Weighting::analog &&
                         estimator != Estimator::track_length) {
      const LaneWalk walk(geometry, scorer, light, problem.albedo, phase.mean_cosine(), estimator,
                          problem.run.escape_radius, problem.run.seed);
      return run_batches(problem.run, book.size(), walk, progress, control);
    } else {
      const RandomWalk<Geometry, Phase, estimator, weighting, Light> walk(
          geometry, phase, light, scorer, problem.albedo, problem.run.escape_radius,
          problem.run.seed);
      return run_batches(problem.run, book.size(), walk, progress, control);
    }
  }

  // No volume tally: nothing is scored at collisions or along flights.
  template <class Geometry, class Phase, class Light = Source>
  BatchOutcome with_estimator(const Geometry& geometry, const Phase& phase,
                              const Light& light) const {
    if (!book.scores_volume()) {
      return run<Geometry, Phase, Estimator::none, Weighting::analog, Light>(geometry, phase,
                                                                                   light);
    }
    if (problem.estimator == Estimator::collision) {
      return run<Geometry, Phase, Estimator::collision, Weighting::analog, Light>(
          geometry, phase, light);
    }
    if constexpr (Geometry::has_surface) {
      throw std::invalid_argument(
          "transport: the track-length estimator runs only in the infinite medium");
    } else {
      return run<Geometry, Phase, Estimator::track_length, Weighting::analog, Light>(
          geometry, phase, light);
    }
  }

  // g = 0 samples isotropically: no HG arithmetic where the scene does not need it.
  template <class Geometry, class Light = Source>
  BatchOutcome with_phase(const Geometry& geometry, const Light& light) const {
    if (problem.g == 0.0) return with_estimator(geometry, IsotropicPhase{}, light);
    return with_estimator(geometry, HenyeyGreenstein{problem.g}, light);
  }
};

// Runs the kernel `select` picks for `problem`: checks its memory, lays out its tallies, runs
// the batches and finishes the tallies (transport() in engine.hpp, which it serves).
TransportOutput run_kernel(const TransportProblem& problem, const ProgressCallback& progress,
                           const RunControl& control,
                           const std::function<BatchOutcome(const Kernel&)>& select);

}  // namespace detail

// transport() for a geometry and a light from outside the transport module; the problem's
// geometry kind, eta, radius and source are not read. Analog absorption.
template <class Geometry, class Light>
TransportOutput transport(const TransportProblem& problem, const Geometry& geometry,
                          const Light& light, const ProgressCallback& progress = {},
                          const RunControl& control = {}) {
  return detail::run_kernel(problem, progress, control, [&](const detail::Kernel& kernel) {
    return kernel.with_phase(geometry, light);
  });
}

}  // namespace scatterlab
