// Cost of the sphere's random walk (the lit sphere): photons/s and ns per scattering event per
// core with the sphere's tallies on (exitance by angle from the lit pole, totals, split by
// order), for the same media as the HalfSpace rows of bench_half_space.cpp, so that the two
// rows of a medium compare the boundary test's cost per event. A pole beam into a sphere of
// 10 mfp stands beside the half-space's beam; a directional light on a sphere of 1 mfp shows the
// cost per photon of the entry (a Fresnel choice and a refraction) over short walks. SphereLanes
// runs the same on the lane walk (transport/lane_walk.hpp), which the engine runs, beside the
// half-space's HalfSpaceLanes rows. The same sphere as a mesh: bench_mesh.cpp.
//
//   ./build/bench/scatterlab_bench --benchmark_filter='Sphere|HalfSpace'
//       --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <vector>

#include "lit_sphere_scene.hpp"
#include "scatterlab/core/phase_function.hpp"
#include "scatterlab/tally/scorer.hpp"
#include "scatterlab/tally/tally_book.hpp"
#include "scatterlab/transport/lane_walk.hpp"
#include "scatterlab/transport/random_walk.hpp"
#include "scatterlab/transport/sphere.hpp"
#include "walk_timing.hpp"

namespace scatterlab {
namespace {

using bench::lit_sphere;

template <class Phase, bool fresnel>
void run_walk(benchmark::State& state, const Phase& phase, const LitObjectSpec& spec) {
  const TransportProblem problem = transport_problem(spec);
  const TallyBook book(problem.tallies, problem.split_by_order);
  const Scorer scorer(problem.axes, book);
  const RandomWalk<Sphere<fresnel>, Phase, Estimator::none> walk(
      Sphere<fresnel>(problem.radius, problem.eta), phase, problem.source, scorer, problem.albedo,
      problem.run.escape_radius, problem.run.seed);
  bench::time_walk(state, walk, book.size());
}

template <class Phase>
void Sphere(benchmark::State& state, Phase phase, LitObjectSpec spec) {
  if (spec.eta != 1.0) return run_walk<Phase, true>(state, phase, spec);
  run_walk<Phase, false>(state, phase, spec);
}

void SphereLanes(benchmark::State& state, LitObjectSpec spec) {
  const TransportProblem problem = transport_problem(spec);
  const TallyBook book(problem.tallies, problem.split_by_order);
  const Scorer scorer(problem.axes, book);
  // (Sphere here is the benchmark above; the geometry is scatterlab::Sphere.)
  const LaneWalk walk(spec.eta == 1.0 ? LaneGeometry(scatterlab::Sphere<false>(problem.radius, 1.0))
                                      : scatterlab::Sphere<true>(problem.radius, problem.eta),
                      scorer, problem.source, problem.albedo, problem.g, Estimator::none,
                      problem.run.escape_radius, problem.run.seed);
  bench::time_walk(state, walk, book.size());
  state.counters["lanes"] = LaneWalk::lanes();
}

const IsotropicPhase iso{};
const HenyeyGreenstein hg075{0.75};

// Benchmark names are not numbers: the formatter would split hg_g0.75 into hg_g0 .75.
// clang-format off
BENCHMARK_CAPTURE(Sphere, pole_R10_iso_albedo0.99_eta1, iso, lit_sphere(0.99, 0.0, 1.0, 10.0, ObjectLight::pole_beam));
BENCHMARK_CAPTURE(Sphere, pole_R10_iso_albedo0.99_eta1.33, iso, lit_sphere(0.99, 0.0, 1.33, 10.0, ObjectLight::pole_beam));
BENCHMARK_CAPTURE(Sphere, pole_R10_hg_g0.75_albedo0.9_eta1.33, hg075, lit_sphere(0.9, 0.75, 1.33, 10.0, ObjectLight::pole_beam));
BENCHMARK_CAPTURE(Sphere, directional_R1_iso_albedo0.99_eta1.33, iso, lit_sphere(0.99, 0.0, 1.33, 1.0, ObjectLight::directional));
BENCHMARK_CAPTURE(Sphere, directional_R10_iso_albedo0.99_eta1.33, iso, lit_sphere(0.99, 0.0, 1.33, 10.0, ObjectLight::directional));
BENCHMARK_CAPTURE(SphereLanes, pole_R10_iso_albedo0.99_eta1, lit_sphere(0.99, 0.0, 1.0, 10.0, ObjectLight::pole_beam));
BENCHMARK_CAPTURE(SphereLanes, pole_R10_iso_albedo0.99_eta1.33, lit_sphere(0.99, 0.0, 1.33, 10.0, ObjectLight::pole_beam));
BENCHMARK_CAPTURE(SphereLanes, pole_R10_hg_g0.75_albedo0.9_eta1.33, lit_sphere(0.9, 0.75, 1.33, 10.0, ObjectLight::pole_beam));
BENCHMARK_CAPTURE(SphereLanes, directional_R1_iso_albedo0.99_eta1.33, lit_sphere(0.99, 0.0, 1.33, 1.0, ObjectLight::directional));
BENCHMARK_CAPTURE(SphereLanes, directional_R10_iso_albedo0.99_eta1.33, lit_sphere(0.99, 0.0, 1.33, 10.0, ObjectLight::directional));
BENCHMARK_CAPTURE(SphereLanes, directional_R100_iso_albedo0.99_eta1.33, lit_sphere(0.99, 0.0, 1.33, 100.0, ObjectLight::directional));
// clang-format on

}  // namespace
}  // namespace scatterlab
