// The hierarchical point cloud's second pass (render/point_octree.hpp): the exitance at points of
// a lit sphere through the octree, per query and per R_d evaluation, for a cluster angle from 0
// (every point summed) up, and for each diffusion model (the table makes them cost the same).
// One thread, three channels (an RGB medium), 16384 points on a unit sphere lit from above.

#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/models/diffusion_profile.hpp"
#include "scatterlab/render/point_cloud.hpp"
#include "scatterlab/render/point_octree.hpp"
#include "scatterlab/render/render_scene.hpp"

namespace scatterlab {
namespace {

struct OctreeFixture {
  PointCloud cloud;
  std::unique_ptr<PointOctree> octree;
  std::vector<Vec3> queries;
  double rho = 0.0;
};

const OctreeFixture& fixture() {
  static const OctreeFixture f = [] {
    OctreeFixture g;
    RenderScene scene;
    scene.mesh = make_sphere(1.0, 48, 96, true);
    scene.eta = 1.3;
    scene.light.position = Vec3(1.0, -1.0, 4.0);
    scene.light.intensity = 16.0;
    scene.light.radius = 0.0;
    PointCloudOptions options;
    options.points = 16384;
    options.relaxation = 20;
    g.cloud = make_point_cloud(scene.mesh, options);
    const std::vector<double> e = point_irradiance(scene, g.cloud, true);
    g.octree = std::make_unique<PointOctree>(cloud_octree(g.cloud, e));
    for (std::size_t i = 0; i < g.cloud.size(); i += 61) g.queries.push_back(g.cloud.positions[i]);
    g.rho = std::sqrt(g.cloud.point_area / std::numbers::pi);
    return g;
  }();
  return f;
}

// range(0): model (0 dipole, 1 better dipole, 2 quantized diffusion); range(1): cluster angle
// in millisteradians (0: unclustered).
void BM_OctreeExitance(benchmark::State& state) {
  const OctreeFixture& f = fixture();
  const ProfileModel model = all_profile_models[state.range(0)];
  const double epsilon = 1e-3 * static_cast<double>(state.range(1));
  // Jensen et al. 2001's skim milk per channel (mm^-1): sigma_s' and sigma_a.
  const std::array<HalfSpaceMedium, 3> media = {HalfSpaceMedium{0.0014, 0.70, 0.0, 1.3},
                                                HalfSpaceMedium{0.0025, 1.22, 0.0, 1.3},
                                                HalfSpaceMedium{0.0142, 1.90, 0.0, 1.3}};
  std::vector<RadialKernel> kernels;
  for (const HalfSpaceMedium& m : media)
    kernels.emplace_back(DiffusionProfile(model, m), f.rho, 2.1);
  std::array<double, 3> m{};
  OctreeQuery query;
  std::uint64_t queries = 0;
  for (auto _ : state) {
    for (const Vec3& x : f.queries) {
      f.octree->exitance(x, epsilon, kernels, m, query);
      benchmark::DoNotOptimize(m.data());
    }
    queries += f.queries.size();
  }
  state.counters["points"] = static_cast<double>(f.cloud.size());
  state.counters["evals_per_query"] =
      static_cast<double>(query.evaluations) / static_cast<double>(queries);
  // Seconds per R_d evaluation of three channels, and per query.
  state.counters["per_eval"] =
      benchmark::Counter(static_cast<double>(query.evaluations),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["per_query"] = benchmark::Counter(
      static_cast<double>(queries), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_OctreeExitance)
    ->ArgsProduct({{0, 1, 2}, {0, 10, 50, 200}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace scatterlab
