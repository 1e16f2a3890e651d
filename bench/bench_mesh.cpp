// Cost of the random walk in an object bounded by a triangle mesh (mesh/mesh_boundary.hpp),
// with the mesh's tallies on (exitance per triangle, totals, split by order): photons/s and ns
// per scattering event per core, for the media of the Sphere and HalfSpace rows
// (bench_lit_sphere.cpp, bench_half_space.cpp).
//   Mesh        a sphere of 10 mfp in 9 216 flat triangles under a beam near its pole, or under
//               the directional light, on the one-photon walk;
//   MeshLanes   the same on the lane walk, as the engine runs a convex object
//               (transport/object_boundary.hpp: the core and the grid of clearances decide the
//               plain events of all lanes at once), beside the analytic sphere's SphereLanes;
//               and a sphere of 100 mfp, whose walks are nearly as long as the half-space's;
//   BlockLanes  the half-space's own scene as a mesh, a block whose top face takes the beam or
//               the directional light, so that its rows differ from HalfSpaceLanes' of the same
//               medium in the boundary test alone (a sphere of 10 mfp also ends its photons'
//               walks sooner, 7-19 events against the half-space's 8-35, and pays a photon's
//               launch and exit over fewer events, as the analytic sphere's rows show);
//   BumpyMesh   a bumpy sphere of as many triangles, which is not convex, on the one-photon walk,
//               as the engine runs it.
//
//   ./build/bench/scatterlab_bench --benchmark_filter='Mesh|BlockLanes|HalfSpaceLanes'
//       --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <memory>
#include <utility>

#include "lit_sphere_scene.hpp"
#include "mesh/mesh_light.hpp"
#include "scatterlab/core/phase_function.hpp"
#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/render/render_scene.hpp"
#include "scatterlab/tally/scorer.hpp"
#include "scatterlab/tally/tally_book.hpp"
#include "scatterlab/transport/lane_walk.hpp"
#include "scatterlab/transport/random_walk.hpp"
#include "walk_timing.hpp"

namespace scatterlab {
namespace {

// The lit sphere's problem on `mesh`, which lies within `radius` of the origin.
LitObjectSpec mesh_spec(TriangleMesh mesh, double albedo, double g, double eta, ObjectLight light,
                        double radius = 10.0) {
  LitObjectSpec spec = bench::lit_sphere(albedo, g, eta, radius, light);
  spec.mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
  return spec;
}

// The one-photon walk (RandomWalk) or the lanes (LaneWalk).
enum class Walker { one_photon, lanes };

template <class Phase, bool fresnel>
void run_mesh_walk(benchmark::State& state, const Phase& phase, const LitObjectSpec& spec,
                   ObjectLight kind, Walker walker) {
  const TransportProblem problem = transport_problem(spec);
  const TallyBook book(problem.tallies, problem.split_by_order);
  const Scorer scorer(problem.axes, book);
  const MeshRayTracer tracer(*spec.mesh);
  const MeshBoundary<fresnel> boundary(tracer, *spec.mesh, spec.eta);
  using Kind = typename MeshLight<fresnel>::Kind;
  // The beam aims at the pole a hair off the axis; the directional light covers the sphere
  // that holds the mesh.
  const MeshLight<fresnel> light(
      boundary, kind == ObjectLight::directional ? Kind::directional : Kind::beam,
      Vec3(1e-3, 2e-3, -2.0 * spec.radius), Vec3::UnitZ(), Vec3::Zero(), spec.radius);
  if (walker == Walker::lanes) {
    const LaneWalk walk(*object_boundary(boundary, light), scorer, problem.albedo,
                        phase.mean_cosine(), Estimator::none, problem.run.escape_radius,
                        problem.run.seed);
    bench::time_walk(state, walk, book.size());
    state.counters["lanes"] = LaneWalk::lanes();
    return;
  }
  const RandomWalk<MeshBoundary<fresnel>, Phase, Estimator::none, Weighting::analog,
                   MeshLight<fresnel>>
      walk(boundary, phase, light, scorer, problem.albedo, problem.run.escape_radius,
           problem.run.seed);
  bench::time_walk(state, walk, book.size());
}

// The lit sphere's problem on `mesh`, within `radius` of the origin, with either walk.
template <class Phase>
void mesh_walk(benchmark::State& state, const Phase& phase, TriangleMesh mesh, double radius,
               double albedo, double g, double eta, ObjectLight kind, Walker walker) {
  const LitObjectSpec spec = mesh_spec(std::move(mesh), albedo, g, eta, kind, radius);
  if (eta != 1.0) return run_mesh_walk<Phase, true>(state, phase, spec, kind, walker);
  run_mesh_walk<Phase, false>(state, phase, spec, kind, walker);
}

// The sphere of radius R in 9 216 flat triangles.
TriangleMesh sphere_mesh(double radius) {
  return make_sphere(radius, 48, 96, false);
}

// A bumpy sphere of as many triangles, which is not convex: radius 0.9 R (1 + 0.1 sin 4 theta
// cos 4 phi), within the sphere of radius R.
TriangleMesh bumpy_mesh(double radius) {
  return make_bumpy_sphere(0.9 * radius, 0.1, 4, 48, 96);
}

// The half-space's scene as a mesh: a block of 200 mfp a side (12 triangles) whose top face, at
// z = -10, takes the beam, or the directional light over a disc of radius 10, at normal
// incidence as the half-space's surface takes its beam. Its photons scatter as often as the
// half-space's (those that reach its far faces, 90 mfp away and more, are too few to count), so
// the two rows differ by the mesh's boundary test and its light alone.
template <class Phase>
void BlockLanes(benchmark::State& state, Phase phase, double albedo, double g, double eta,
                ObjectLight kind) {
  TriangleMesh block = make_box(Vec3(100.0, 100.0, 100.0));
  for (Vec3& p : block.positions) p.z() += 90.0;
  mesh_walk(state, phase, std::move(block), 10.0, albedo, g, eta, kind, Walker::lanes);
}

template <class Phase>
void Mesh(benchmark::State& state, Phase phase, double albedo, double g, double eta,
          ObjectLight kind) {
  mesh_walk(state, phase, sphere_mesh(10.0), 10.0, albedo, g, eta, kind, Walker::one_photon);
}

template <class Phase>
void MeshLanes(benchmark::State& state, Phase phase, double albedo, double g, double eta,
               ObjectLight kind, double radius = 10.0) {
  mesh_walk(state, phase, sphere_mesh(radius), radius, albedo, g, eta, kind, Walker::lanes);
}

template <class Phase>
void BumpyMesh(benchmark::State& state, Phase phase, double albedo, double g, double eta,
               ObjectLight kind) {
  mesh_walk(state, phase, bumpy_mesh(10.0), 10.0, albedo, g, eta, kind, Walker::one_photon);
}

const IsotropicPhase iso{};
const HenyeyGreenstein hg075{0.75};

// Benchmark names are not numbers: the formatter would split hg_g0.75 into hg_g0 .75.
// clang-format off
BENCHMARK_CAPTURE(Mesh, beam_R10_iso_albedo0.99_eta1, iso, 0.99, 0.0, 1.0, ObjectLight::beam);
BENCHMARK_CAPTURE(Mesh, beam_R10_iso_albedo0.99_eta1.33, iso, 0.99, 0.0, 1.33, ObjectLight::beam);
BENCHMARK_CAPTURE(Mesh, beam_R10_hg_g0.75_albedo0.9_eta1.33, hg075, 0.9, 0.75, 1.33, ObjectLight::beam);
BENCHMARK_CAPTURE(Mesh, directional_R10_iso_albedo0.99_eta1.33, iso, 0.99, 0.0, 1.33, ObjectLight::directional);
BENCHMARK_CAPTURE(MeshLanes, beam_R10_iso_albedo0.99_eta1, iso, 0.99, 0.0, 1.0, ObjectLight::beam);
BENCHMARK_CAPTURE(MeshLanes, beam_R10_iso_albedo0.99_eta1.33, iso, 0.99, 0.0, 1.33, ObjectLight::beam);
BENCHMARK_CAPTURE(MeshLanes, beam_R10_hg_g0.75_albedo0.9_eta1.33, hg075, 0.9, 0.75, 1.33, ObjectLight::beam);
BENCHMARK_CAPTURE(MeshLanes, directional_R10_iso_albedo0.99_eta1.33, iso, 0.99, 0.0, 1.33, ObjectLight::directional);
BENCHMARK_CAPTURE(MeshLanes, directional_R100_iso_albedo0.99_eta1.33, iso, 0.99, 0.0, 1.33, ObjectLight::directional, 100.0);
BENCHMARK_CAPTURE(BlockLanes, beam_iso_albedo0.99_eta1, iso, 0.99, 0.0, 1.0, ObjectLight::beam);
BENCHMARK_CAPTURE(BlockLanes, beam_iso_albedo0.99_eta1.33, iso, 0.99, 0.0, 1.33, ObjectLight::beam);
BENCHMARK_CAPTURE(BlockLanes, beam_hg_g0.75_albedo0.9_eta1.33, hg075, 0.9, 0.75, 1.33, ObjectLight::beam);
BENCHMARK_CAPTURE(BlockLanes, directional_iso_albedo0.99_eta1.33, iso, 0.99, 0.0, 1.33, ObjectLight::directional);
BENCHMARK_CAPTURE(BumpyMesh, directional_R9_iso_albedo0.99_eta1.33, iso, 0.99, 0.0, 1.33, ObjectLight::directional);
// clang-format on

}  // namespace
}  // namespace scatterlab
