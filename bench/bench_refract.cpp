// Refractive path search (Walter et al. 2009) on the bumpy sphere of ~1e4 triangles: paths per
// second and triangles tested per query with and without the position-normal tree, heuristic vs
// guaranteed mode, and time against the Newton tolerance (Holzschuch 2013, Fig. 11).

#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/refract/refractive_solver.hpp"

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

}  // namespace
}  // namespace scatterlab
