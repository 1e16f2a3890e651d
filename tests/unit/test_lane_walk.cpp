// The lane walk (transport/lane_walk.hpp) against the one-photon RandomWalk on the same photons,
// in the infinite medium, the half-space, the sphere and the layered slab.
// Both draw the same Philox words and make the same absorption choices, so they follow the same
// paths; only the last bits of a free path's log, of a turned direction and of the order of the
// adds differ. Every photon scatters the same number of times, and every tally cell agrees to
// 1e-9 of the largest (a cell that a collision left by rounding would differ by one event: about
// 1e-4 of these tallies' largest cells).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "every_target.hpp"
#include "scatterlab/core/phase_function.hpp"
#include "scatterlab/tally/scorer.hpp"
#include "scatterlab/tally/tally_book.hpp"
#include "scatterlab/transport/half_space.hpp"
#include "scatterlab/transport/infinite_medium.hpp"
#include "scatterlab/transport/lane_walk.hpp"
#include "scatterlab/transport/layered_slab.hpp"
#include "scatterlab/transport/lit_object.hpp"
#include "scatterlab/transport/random_walk.hpp"
#include "scatterlab/transport/searchlight.hpp"
#include "scatterlab/transport/simulate.hpp"
#include "scatterlab/transport/slab.hpp"
#include "scatterlab/transport/sphere.hpp"

namespace scatterlab {
namespace {

using testing::on_every_target;

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

// The two walks on photons [first, last) into tallies of `cells` values.
template <class OneWalk>
void expect_same_sums(const OneWalk& one, const LaneWalk& lanes, std::size_t cells,
                      std::uint64_t first, std::uint64_t last) {
  const Walked a = walk_photons(one, cells, first, last);
  const Walked b = walk_photons(lanes, cells, first, last);
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

// `geometry` on RandomWalk and on LaneWalk, with the collision estimator. By default a range
// that does not start at 0 and is no multiple of any lane count.
template <class Geometry, class Phase>
void expect_same_paths(const TransportProblem& problem, const Geometry& geometry,
                       const Phase& phase, std::uint64_t first = 1001, std::uint64_t last = 4004) {
  const TallyBook book(problem.tallies, problem.split_by_order);
  const Scorer scorer(problem.axes, book);
  const RandomWalk<Geometry, Phase, Estimator::collision> one(
      geometry, phase, problem.source, scorer, problem.albedo, problem.run.escape_radius,
      problem.run.seed);
  on_every_target([&] {
    const LaneWalk lanes(geometry, scorer, problem.source, problem.albedo, problem.g,
                         Estimator::collision, problem.run.escape_radius, problem.run.seed);
    expect_same_sums(one, lanes, book.size(), first, last);
  });
}

template <class Phase>
void expect_same_paths(const InfiniteMediumSpec& spec, const Phase& phase) {
  expect_same_paths(transport_problem(spec), InfiniteMedium{}, phase);
}

// The searchlight's half-space, its fluence tally on: matched (eta = 1) or behind a Fresnel
// boundary, whose choices draw from the photon's stream.
template <class Phase>
void expect_same_paths_in_half_space(double albedo, double g, double eta, double incidence,
                                     const Phase& phase) {
  HalfSpaceSpec spec;
  spec.medium.albedo = albedo;
  spec.medium.g = g;
  spec.eta = eta;
  spec.incidence_deg = incidence;
  const TransportProblem problem = transport_problem(spec);
  if (eta == 1.0) {
    expect_same_paths(problem, HalfSpace<false>(eta), phase);
  } else {
    expect_same_paths(problem, HalfSpace<true>(eta), phase);
  }
}

// The lit sphere: its exitance by angle from the lit pole, split by order, under the directional
// light (whose photons the surface may reflect before they enter) or a beam at the pole; matched,
// or behind a Fresnel boundary whose choices draw from the photon's stream (eta 1.4 with total
// internal reflection, and 0.8).
template <class Phase>
void expect_same_paths_in_the_sphere(double albedo, double g, double eta, double radius,
                                     ObjectLight light, const Phase& phase) {
  LitObjectSpec spec;
  spec.medium.albedo = albedo;
  spec.medium.g = g;
  spec.eta = eta;
  spec.radius = radius;
  spec.light = light;
  const TransportProblem problem = transport_problem(spec);
  if (eta == 1.0) {
    expect_same_paths(problem, Sphere<false>(radius, 1.0), phase);
  } else {
    expect_same_paths(problem, Sphere<true>(radius, eta), phase);
  }
}

InfiniteMediumSpec scene(double albedo, double g) {
  InfiniteMediumSpec spec;
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
  InfiniteMediumSpec spec = scene(0.95, 0.3);
  spec.set_source(SourceKind::point);
  spec.tallies.radiance = true;
  spec.run.escape_radius = 4.0;  // most photons escape before they are absorbed
  expect_same_paths(spec, HenyeyGreenstein{0.3});
}

TEST(LaneWalk, FollowsTheOnePhotonWalkPastPhoton2To32) {
  // The photon index's high word is the second counter word.
  const std::uint64_t first = (std::uint64_t{1} << 32) - 300;
  expect_same_paths(transport_problem(scene(0.9, 0.0)), InfiniteMedium{}, IsotropicPhase{}, first,
                    first + 700);
}

TEST(LaneWalk, FollowsTheOnePhotonWalkInTheHalfSpace) {
  expect_same_paths_in_half_space(0.99, 0.0, 1.0, 0.0, IsotropicPhase{});
  expect_same_paths_in_half_space(0.9, 0.75, 1.0, 30.0, HenyeyGreenstein{0.75});
  expect_same_paths_in_half_space(0.99, 0.0, 1.4, 0.0, IsotropicPhase{});
  expect_same_paths_in_half_space(0.95, 0.5, 0.8, 45.0, HenyeyGreenstein{0.5});
}

TEST(LaneWalk, FollowsTheOnePhotonWalkInTheSphere) {
  expect_same_paths_in_the_sphere(0.99, 0.0, 1.0, 3.0, ObjectLight::directional, IsotropicPhase{});
  expect_same_paths_in_the_sphere(0.9, 0.75, 1.4, 5.0, ObjectLight::directional,
                                  HenyeyGreenstein{0.75});
  expect_same_paths_in_the_sphere(0.95, -0.3, 1.4, 2.0, ObjectLight::pole_beam,
                                  HenyeyGreenstein{-0.3});
  expect_same_paths_in_the_sphere(0.99, 0.5, 0.8, 1.0, ObjectLight::directional,
                                  HenyeyGreenstein{0.5});
}

// MCML's layered slab with every kind of interface and layer: a clear first layer, mismatched
// inner interfaces (total internal reflection included), g > 0, g = 0 and g < 0, a semi-infinite
// last layer, and an index below different from the one above; every MCML tally on, split by
// order. Analog, and with implicit capture (its weights and roulette ride in the lanes).
template <Weighting weighting>
void expect_same_paths_in_the_slab() {
  const auto layer = [](double mu_a, double mu_s, double g, double n, double thickness) {
    SlabLayerSpec l;
    l.mu_a = mu_a, l.mu_s = mu_s, l.g = g, l.n = n, l.thickness = thickness;
    return l;
  };
  LayeredSlabSpec spec;
  spec.layers = {layer(0.0, 0.0, 0.0, 1.5, 0.05), layer(1.0, 100.0, 0.9, 1.37, 0.1),
                 layer(1.0, 10.0, -0.5, 1.45, 0.1),
                 layer(2.0, 10.0, 0.0, 1.33, std::numeric_limits<double>::infinity())};
  spec.n_above = 1.0;
  spec.n_below = 1.2;
  spec.weighting = weighting;
  spec.validate();
  const TransportProblem problem = transport_problem(spec);
  const TallyBook book(problem.tallies, problem.split_by_order);
  const Scorer scorer(problem.axes, book);
  const Slab slab(problem.layers, problem.n_above, problem.n_below);
  const RandomWalk<Slab, IsotropicPhase, Estimator::none, weighting> one(
      slab, IsotropicPhase{}, problem.source, scorer, problem.albedo, problem.run.escape_radius,
      problem.run.seed);
  on_every_target([&] {
    const LaneWalk lanes(slab, weighting, scorer, problem.source, problem.run.escape_radius,
                         problem.run.seed);
    expect_same_sums(one, lanes, book.size(), 1001, 4004);
  });
}

TEST(LaneWalk, FollowsTheOnePhotonWalkInTheLayeredSlab) {
  expect_same_paths_in_the_slab<Weighting::analog>();
}

TEST(LaneWalk, FollowsTheOnePhotonWalkInTheLayeredSlabWithImplicitCapture) {
  expect_same_paths_in_the_slab<Weighting::implicit_capture>();
}

// Eight photons are in flight whatever the vector width, so their scores reach the buffer in one
// order: every instruction set that fuses multiplies and adds (AVX2, AVX-512) gives the same bits.
// The infinite medium's flux and mean depth, sums of cosines and depths, are those that an order
// of adds would move. Skipped on a machine with fewer than two such instruction sets; the
// digests of tests/bitwise, made with AVX-512, hold an AVX2 machine to the same bits.
TEST(LaneWalk, GivesTheSameBitsOnEveryInstructionSetWithFusedMultiplyAdds) {
  const TransportProblem problem = transport_problem(scene(0.9, 0.7));
  const TallyBook book(problem.tallies, problem.split_by_order);
  const Scorer scorer(problem.axes, book);
  std::vector<std::vector<double>> runs;
  on_every_target([&] {
    const std::int64_t fused = HWY_AVX2 | HWY_AVX3 | HWY_AVX3_DL;
    if ((hwy::SupportedTargets() & fused) == 0) return;
    const LaneWalk lanes(InfiniteMedium{}, scorer, problem.source, problem.albedo, problem.g,
                         Estimator::collision, problem.run.escape_radius, problem.run.seed);
    runs.push_back(walk_photons(lanes, book.size(), 1001, 4004).sums);
  });
  if (runs.size() < 2) GTEST_SKIP() << "one instruction set with fused multiply-adds here";
  for (std::size_t i = 1; i < runs.size(); ++i) EXPECT_EQ(runs[i], runs[0]);
}

TEST(LaneWalk, HasOneToEightLanes) {
  EXPECT_GE(LaneWalk::lanes(), 1);
  EXPECT_LE(LaneWalk::lanes(), 8);
}

TEST(LaneWalk, RefusesWhatItDoesNotRun) {
  const TransportProblem problem = transport_problem(scene(0.9, 0.0));
  const TallyBook book(problem.tallies, problem.split_by_order);
  const Scorer scorer(problem.axes, book);
  EXPECT_THROW(LaneWalk(InfiniteMedium{}, scorer, problem.source, 0.9, 0.0, Estimator::track_length,
                        problem.run.escape_radius, 1),
               std::invalid_argument);
  // A slab without its weighting, and the sphere's light on another geometry.
  const Slab slab({SlabLayer{}}, 1.0, 1.0);
  EXPECT_THROW(LaneWalk(LaneGeometry(slab), scorer, problem.source, 0.9, 0.0, Estimator::none,
                        problem.run.escape_radius, 1),
               std::invalid_argument);
  Source sphere_light = problem.source;
  sphere_light.kind = Source::Kind::sphere_light;
  EXPECT_THROW(LaneWalk(HalfSpace<false>(1.0), scorer, sphere_light, 0.9, 0.0, Estimator::none,
                        problem.run.escape_radius, 1),
               std::invalid_argument);
  EXPECT_NO_THROW(LaneWalk(Sphere<false>(2.0, 1.0), scorer, sphere_light, 0.9, 0.0,
                           Estimator::none, problem.run.escape_radius, 1));
}

}  // namespace
}  // namespace scatterlab
