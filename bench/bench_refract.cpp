// Refractive path search (Walter et al. 2009) on the bumpy sphere of ~1e4 triangles: paths per
// second and triangles tested per query with and without the position-normal tree, heuristic vs
// guaranteed mode, and time against the Newton tolerance (Holzschuch 2013, Fig. 11).
// Along eye rays (Holzschuch §3.2): support intervals with hierarchical pruning against the tree
// or every triangle at every sample point.

#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/refract/refractive_solver.hpp"
#include "scatterlab/refract/support_interval.hpp"

namespace scatterlab {
namespace {

struct Query {
  Vec3 v;
  Light light;
};

std::vector<Query> make_queries(int count) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform;
  std::vector<Query> queries;
  for (int i = 0; i < count; ++i) {
    const Vec3 dv = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    const Vec3 dl = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    queries.push_back({0.8 * std::cbrt(uniform(rng)) * dv, Light::point((1.5 + 1.5 * uniform(rng)) * dl)});
  }
  return queries;
}

const TriangleMesh& bumpy_sphere() {
  static const TriangleMesh mesh = make_bumpy_sphere(1.0, 0.05, 6, 71, 72);
  return mesh;
}

// range(0): 0 heuristic, 1 guaranteed; range(1): 1 with the tree, 0 every triangle;
// range(2): -log10 of the Newton tolerance.
void BM_RefractivePaths(benchmark::State& state) {
  RefractionOptions options;
  options.mode = state.range(0) == 0 ? SearchMode::heuristic : SearchMode::guaranteed;
  options.use_tree = state.range(1) == 1;
  options.newton_tolerance = std::pow(10.0, -double(state.range(2)));
  const RefractiveSolver solver(bumpy_sphere(), 1.5, options);
  const std::vector<Query> queries = make_queries(64);
  RefractionStats stats;
  std::vector<RefractionPath> paths;
  std::size_t next = 0;
  for (auto _ : state) {
    paths.clear();
    const Query& q = queries[next++ % queries.size()];
    solver.find_paths(q.v, q.light, paths, stats);
    benchmark::DoNotOptimize(paths.data());
  }
  const double queries_run = double(stats.queries);
  state.counters["paths/s"] = benchmark::Counter(double(stats.paths), benchmark::Counter::kIsRate);
  state.counters["paths/query"] = double(stats.paths) / queries_run;
  state.counters["triangles/query"] = double(stats.triangles_tested) / queries_run;
  state.counters["nodes/query"] = double(stats.nodes_visited) / queries_run;
  state.counters["subtriangles/query"] = double(stats.subtriangles) / queries_run;
  state.counters["newton_iters/query"] = double(stats.newton_iterations) / queries_run;
  state.counters["undecided"] = double(stats.undecided_at_depth_limit);
}
BENCHMARK(BM_RefractivePaths)
    ->ArgNames({"guaranteed", "tree", "tol_exp"})
    ->Args({0, 1, 12})
    ->Args({1, 1, 12})
    ->Args({0, 0, 12})
    ->Args({1, 0, 12})
    ->Args({0, 1, 4})
    ->Args({0, 1, 8})
    ->Args({0, 1, 14})
    ->Unit(benchmark::kMicrosecond);

struct EyeRay {
  EyeSegment segment;
  Light light;
};

// Chords of the ball r < 0.8 (inside the bumpy sphere) with a point light outside.
std::vector<EyeRay> make_eye_rays(int count) {
  std::mt19937_64 rng(17);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform;
  const auto inside = [&] {
    return Vec3(0.8 * std::cbrt(uniform(rng)) *
                Vec3(normal(rng), normal(rng), normal(rng)).normalized());
  };
  std::vector<EyeRay> rays;
  for (int i = 0; i < count; ++i) {
    const Vec3 a = inside(), b = inside();
    const Vec3 dl = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    rays.push_back({{a, (b - a).normalized(), 0.0, (b - a).norm()},
                    Light::point((1.5 + 1.5 * uniform(rng)) * dl)});
  }
  return rays;
}

// Per eye ray: support intervals and pruning alone (range(0) = 0), or all paths at range(1)
// regular sample points found by range(0) = 1: intervals, then only the triangles whose interval holds
// the sample; 2: the tree at every sample; 3: every triangle at every sample.
void BM_EyeRaySupports(benchmark::State& state) {
  const int mode = static_cast<int>(state.range(0));
  RefractionOptions options;
  options.use_tree = mode != 3;
  const RefractiveSolver solver(bumpy_sphere(), 1.5, options);
  const std::vector<EyeRay> rays = make_eye_rays(16);
  const int samples = static_cast<int>(state.range(1));
  SupportStats support_stats;
  RefractionStats path_stats;
  std::vector<TriangleSupport> supports;
  std::vector<RefractionPath> paths;
  double interval_fraction = 0.0;
  std::size_t next = 0, rays_run = 0;
  for (auto _ : state) {
    const EyeRay& ray = rays[next++ % rays.size()];
    ++rays_run;
    const double length = ray.segment.t1 - ray.segment.t0;
    supports.clear();
    if (mode <= 1) {
      find_segment_supports(RefractedLight(solver, ray.light), ray.segment, supports,
                            support_stats);
      for (const TriangleSupport& t : supports) interval_fraction += t.interval.length() / length;
    }
    if (mode == 0) continue;
    for (int i = 0; i < samples; ++i) {
      const double x = ray.segment.t0 + length * (i + 0.5) / samples;
      const Vec3 v = ray.segment.at(x);
      paths.clear();
      if (mode == 1) {
        for (const TriangleSupport& t : supports) {
          if (t.interval.contains(x)) solver.find_paths_through(t.triangle, v, ray.light, paths, path_stats);
        }
        solver.merge_duplicates(paths, 0, path_stats);
      } else {
        solver.find_paths(v, ray.light, paths, path_stats);
      }
      benchmark::DoNotOptimize(paths.data());
    }
  }
  const double n = double(rays_run);
  state.counters["paths/ray"] = double(path_stats.paths) / n;
  state.counters["tri_searches/ray"] = double(path_stats.triangles_tested) / n;
  if (mode <= 1) {
    state.counters["kept_tris/ray"] = double(support_stats.supports) / n;
    state.counters["nodes/ray"] = double(support_stats.nodes_visited) / n;
    state.counters["interval_tris/ray"] = double(support_stats.triangles_tested) / n;
    state.counters["mean_interval_frac"] =
        support_stats.supports > 0 ? interval_fraction / double(support_stats.supports) : 0.0;
  }
}
// 16 iterations: each ray once, so the modes' per-ray counters are over the same rays.
BENCHMARK(BM_EyeRaySupports)
    ->ArgNames({"mode", "samples"})
    ->Args({0, 0})
    ->Args({1, 32})
    ->Args({2, 32})
    ->Args({3, 32})
    ->Args({1, 128})
    ->Args({2, 128})
    ->Iterations(16)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace scatterlab
