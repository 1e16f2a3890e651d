// The lane walk (transport/lane_walk.hpp) against the one-photon RandomWalk on the same photons,
// in the infinite medium and the half-space.
// Both draw the same Philox words and make the same absorption choices, so they follow the same
// paths; only the last bits of a free path's log, of a turned direction and of the order of the
// adds differ. Every photon scatters the same number of times, and every tally cell agrees to
// 1e-9 of the largest (a cell that a collision left by rounding would differ by one event: about
// 1e-4 of these tallies' largest cells).
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "scatterlab/core/phase_function.hpp"
#include "scatterlab/tally/scorer.hpp"
#include "scatterlab/tally/tally_book.hpp"
#include "scatterlab/transport/half_space.hpp"
#include "scatterlab/transport/infinite_medium.hpp"
#include "scatterlab/transport/lane_walk.hpp"
#include "scatterlab/transport/random_walk.hpp"
#include "scatterlab/transport/searchlight.hpp"
#include "scatterlab/transport/simulate.hpp"

namespace scatterlab {
namespace {

struct Walked {
  std::vector<double> sums;
  std::uint64_t scatterings = 0;
};

template <class Walk>
Walked walk_photons(const Walk& walk, std::size_t cells, std::uint64_t first, std::uint64_t last) {
  Walked w;
  w.sums.assign(cells, 0.0);
  auto scratch = walk.make_scratch();
  w.scatterings = walk.run(first, last, w.sums.data(), scratch);
  return w;
}

// `geometry` and `kind` the same geometry, for RandomWalk and LaneWalk.
template <class Geometry, class Phase>
void expect_same_paths_here(const TransportProblem& problem, const Geometry& geometry,
                            LaneWalk::Geometry kind, const Phase& phase, std::uint64_t first,
                            std::uint64_t last) {
  const TallyBook book(problem.tallies, problem.split_by_order);
  const Scorer scorer(problem.axes, book);
  const RandomWalk<Geometry, Phase, VolumeEstimator::collision> one(
      geometry, phase, problem.source, scorer, problem.albedo, problem.run.escape_radius,
      problem.run.seed);
  const LaneWalk lanes(kind, problem.eta, scorer, problem.source, problem.albedo, problem.g,
                       VolumeEstimator::collision, problem.run.escape_radius, problem.run.seed);
  const Walked a = walk_photons(one, book.size(), first, last);
  const Walked b = walk_photons(lanes, book.size(), first, last);
  EXPECT_EQ(a.scatterings, b.scatterings);
  ASSERT_GT(a.scatterings, 0u);
  double largest = 0.0;
  for (const double v : a.sums) largest = std::max(largest, std::abs(v));
  std::size_t differing = 0;
  for (std::size_t i = 0; i < a.sums.size(); ++i) {
    differing += std::abs(a.sums[i] - b.sums[i]) > 1e-9 * largest;
  }
  EXPECT_EQ(differing, 0u) << "of " << a.sums.size() << " cells";
}

// On every instruction set this machine runs, each in turn.
// By default a range that does not start at 0 and is no multiple of any lane count.
template <class Geometry, class Phase>
void expect_same_paths(const TransportProblem& problem, const Geometry& geometry,
                       LaneWalk::Geometry kind, const Phase& phase, std::uint64_t first = 1001,
                       std::uint64_t last = 4004) {
  for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
    SCOPED_TRACE(hwy::TargetName(target));
    hwy::SetSupportedTargetsForTest(target);
    expect_same_paths_here(problem, geometry, kind, phase, first, last);
  }
  hwy::SetSupportedTargetsForTest(0);  // back to the best the machine has
}

template <class Phase>
void expect_same_paths(const SimulationSpec& spec, const Phase& phase) {
  expect_same_paths(transport_problem(spec), InfiniteMedium{}, LaneWalk::Geometry::infinite_medium,
                    phase);
}

// The searchlight's half-space, its fluence tally on: matched (eta = 1) or behind a Fresnel
// boundary, whose choices draw from the photon's stream.
template <class Phase>
void expect_same_paths_in_half_space(double albedo, double g, double eta, double incidence,
                                     const Phase& phase) {
  SearchlightSpec spec;
  spec.medium.albedo = albedo;
  spec.medium.g = g;
  spec.eta = eta;
  spec.incidence_deg = incidence;
  const TransportProblem problem = transport_problem(spec);
  if (eta == 1.0) {
    expect_same_paths(problem, HalfSpace<false>(eta), LaneWalk::Geometry::half_space, phase);
  } else {
    expect_same_paths(problem, HalfSpace<true>(eta), LaneWalk::Geometry::fresnel_half_space, phase);
  }
}

SimulationSpec scene(double albedo, double g) {
  SimulationSpec spec;
  spec.medium.albedo = albedo;
  spec.medium.g = g;
  spec.tallies.radiance = true;  // fluence, flux and radiance, split by order
  spec.tallies.estimator = Estimator::collision;
  return spec;
}

TEST(LaneWalk, FollowsTheOnePhotonWalkIsotropic) {
  expect_same_paths(scene(0.99, 0.0), IsotropicPhase{});
}

TEST(LaneWalk, FollowsTheOnePhotonWalkHenyeyGreenstein) {
  expect_same_paths(scene(0.9, 0.75), HenyeyGreenstein{0.75});
  expect_same_paths(scene(0.5, -0.6), HenyeyGreenstein{-0.6});
}

TEST(LaneWalk, FollowsTheOnePhotonWalkFromAPointSourceToAnEscapeRadius) {
  SimulationSpec spec = scene(0.95, 0.3);
  spec.set_source(SourceKind::point);
  spec.tallies.radiance = true;
  spec.run.escape_radius = 4.0;  // most photons escape before they are absorbed
  expect_same_paths(spec, HenyeyGreenstein{0.3});
}

TEST(LaneWalk, FollowsTheOnePhotonWalkPastPhoton2To32) {
  // The photon index's high word is the second counter word.
  const std::uint64_t first = (std::uint64_t{1} << 32) - 300;
  expect_same_paths(transport_problem(scene(0.9, 0.0)), InfiniteMedium{},
                    LaneWalk::Geometry::infinite_medium, IsotropicPhase{}, first, first + 700);
}

TEST(LaneWalk, FollowsTheOnePhotonWalkInTheHalfSpace) {
  expect_same_paths_in_half_space(0.99, 0.0, 1.0, 0.0, IsotropicPhase{});
  expect_same_paths_in_half_space(0.9, 0.75, 1.0, 30.0, HenyeyGreenstein{0.75});
  expect_same_paths_in_half_space(0.99, 0.0, 1.4, 0.0, IsotropicPhase{});
  expect_same_paths_in_half_space(0.95, 0.5, 0.8, 45.0, HenyeyGreenstein{0.5});
}

TEST(LaneWalk, HasOneToEightLanes) {
  EXPECT_GE(LaneWalk::lanes(), 1);
  EXPECT_LE(LaneWalk::lanes(), 8);
}

TEST(LaneWalk, RefusesWhatItDoesNotRun) {
  const TransportProblem problem = transport_problem(scene(0.9, 0.0));
  const TallyBook book(problem.tallies, problem.split_by_order);
  const Scorer scorer(problem.axes, book);
  EXPECT_THROW(LaneWalk(LaneWalk::Geometry::infinite_medium, 1.0, scorer, problem.source, 0.9, 0.0,
                        VolumeEstimator::track_length, problem.run.escape_radius, 1),
               std::invalid_argument);
}

}  // namespace
}  // namespace scatterlab
