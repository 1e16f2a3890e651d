// Completeness of the refractive path search on curved meshes (Walter et al. 2009, §3.3-3.4):
// the guaranteed (Krawczyk) mode must find every path a dense brute-force search finds, the
// heuristic mode at least 99.9 % of them; every path obeys Snell's law about N_s to 1e-10 and the
// sidedness conditions. The tree must not lose paths the plain loop finds.

#include <gtest/gtest.h>

#include <iostream>
#include <random>

#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/refract/refractive_solver.hpp"
#include "scatterlab/refract/triangle_search.hpp"

namespace scatterlab {
namespace {

struct Query {
  Vec3 v;
  Light light;
};

// Brute force: Newton (steps of at most 0.2) from a dense barycentric grid (spacing 1/n) of
// every triangle wherever |f| < threshold there (1/16 and 0.3; 1/8 and 0.2 on the small
// triangles of the bumpy sphere), sharing
// no pruning or stopping rule with the solver.
std::vector<RefractionPath> brute_force(const RefractiveSolver& solver, const Query& query,
                                        int n, double threshold) {
  const PathQuery q(query.v, query.light, solver.eta());
  RefractionOptions options;
  options.max_newton_iterations = 30;
  RefractionStats stats;
  std::vector<RefractionPath> found;
  for (std::size_t t = 0; t < solver.triangle_count(); ++t) {
    const RefractiveTriangle& tri = solver.triangle(t);
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) {
        const Eigen::Vector2d start(double(i) / n, double(j) / n);
        if (!(evaluate_residual(tri, q, start.x(), start.y()).f.norm() < threshold)) continue;
        const auto ab = newton_2d(tri, q, start, 0.2, options, stats);
        if (!ab) continue;
        if (auto path = accept_path(tri, q, ab->x(), ab->y())) {
          bool seen = false;
          for (const RefractionPath& p : found) seen = seen || (p.point - path->point).norm() < 1e-7;
          if (!seen) found.push_back(*path);
        }
      }
    }
  }
  return found;
}

std::size_t count_found(const std::vector<RefractionPath>& reference,
                        const std::vector<RefractionPath>& paths) {
  std::size_t hits = 0;
  for (const RefractionPath& r : reference) {
    for (const RefractionPath& p : paths) {
      if ((p.point - r.point).norm() < 1e-7) {
        ++hits;
        break;
      }
    }
  }
  return hits;
}

void check_paths(const std::vector<RefractionPath>& paths, const Query& query, double eta) {
  for (const RefractionPath& p : paths) {
    EXPECT_LE((p.omega_l + eta * p.omega_v).cross(p.shading_normal).norm(), 1e-10);
    EXPECT_GT(p.omega_l.dot(p.shading_normal), 0.0);
    EXPECT_LT(p.omega_v.dot(p.shading_normal), 0.0);
    EXPECT_LE((p.point + p.distance_v * p.omega_v - query.v).norm(), 1e-12);
  }
}

struct Completeness {
  std::size_t reference = 0, guaranteed = 0, heuristic = 0, tree_lost = 0, extra = 0;
  std::size_t union_size = 0, heuristic_of_union = 0;
};

Completeness run(const TriangleMesh& mesh, double eta, const std::vector<Query>& queries,
                 int grid = 16, double threshold = 0.3) {
  RefractionOptions heuristic_options;
  RefractionOptions guaranteed_options;
  guaranteed_options.mode = SearchMode::guaranteed;
  RefractionOptions loop_options = guaranteed_options;
  loop_options.use_tree = false;
  const RefractiveSolver heuristic(mesh, eta, heuristic_options);
  const RefractiveSolver guaranteed(mesh, eta, guaranteed_options);
  const RefractiveSolver loop(mesh, eta, loop_options);
  Completeness c;
  for (const Query& query : queries) {
    const auto reference = brute_force(guaranteed, query, grid, threshold);
    const auto g = guaranteed.find_paths(query.v, query.light);
    const auto h = heuristic.find_paths(query.v, query.light);
    check_paths(g, query, eta);
    check_paths(h, query, eta);
    c.reference += reference.size();
    c.guaranteed += count_found(reference, g);
    c.heuristic += count_found(reference, h);
    c.extra += g.size() - count_found(g, reference);
    // Every path either search found (all verified by check_paths): the heuristic's target.
    std::vector<RefractionPath> all = g;
    for (const RefractionPath& r : reference) {
      if (count_found({r}, g) == 0) all.push_back(r);
    }
    c.union_size += all.size();
    c.heuristic_of_union += count_found(all, h);
    c.tree_lost += count_found(loop.find_paths(query.v, query.light), g) < g.size();
  }
  return c;
}

std::vector<Query> queries_in_ball(int count, double inner_radius, double light_min,
                                   double light_max, std::uint64_t seed, bool directional) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform;
  std::vector<Query> queries;
  for (int i = 0; i < count; ++i) {
    const Vec3 dv = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    const Vec3 dl = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    const Vec3 v = inner_radius * std::cbrt(uniform(rng)) * dv;
    const double distance = light_min + (light_max - light_min) * uniform(rng);
    queries.push_back({v, directional ? Light::directional(dl) : Light::point(distance * dl)});
  }
  return queries;
}

void report(const char* name, const Completeness& c) {
  std::cout << name << ": brute force " << c.reference << " paths; guaranteed found "
            << c.guaranteed << " (+" << c.extra << " more), heuristic " << c.heuristic
            << "; heuristic found " << c.heuristic_of_union << " of the " << c.union_size
            << " paths either search found\n";
  EXPECT_GT(c.reference, 0u);
  EXPECT_EQ(c.guaranteed, c.reference);
  EXPECT_GE(double(c.heuristic_of_union), 0.999 * double(c.union_size));
  EXPECT_EQ(c.tree_lost, 0u);
}

TEST(RefractiveCompleteness, SmoothSphere) {
  const TriangleMesh sphere = make_sphere(1.0, 12, 24, true);
  report("sphere eta 1.5", run(sphere, 1.5, queries_in_ball(20, 0.8, 1.5, 4.0, 1, false)));
  report("sphere eta 0.75", run(sphere, 0.75, queries_in_ball(10, 0.8, 1.5, 4.0, 2, false)));
  report("sphere directional", run(sphere, 1.5, queries_in_ball(10, 0.8, 0, 0, 3, true)));
}

TEST(RefractiveCompleteness, BumpySphere) {
  const TriangleMesh bumpy = make_bumpy_sphere(1.0, 0.05, 6, 71, 72);
  report("bumpy sphere eta 1.5", run(bumpy, 1.5, queries_in_ball(4, 0.8, 1.5, 3.0, 4, false), 8, 0.2));
  // Close to the bumps and lit from nearby: several paths per query.
  report("bumpy sphere near surface",
         run(bumpy, 1.5, queries_in_ball(4, 0.93, 1.1, 1.4, 6, false), 8, 0.2));
}

TEST(RefractiveCompleteness, RoundedTile) {
  const TriangleMesh tile = make_rounded_tile(1.0, 1.0, 0.25, 0.3, 16, 32);
  std::vector<Query> queries;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 20; ++i) {
    queries.push_back({Vec3(0.6 * u(rng), 0.6 * u(rng), 0.15 * u(rng)),
                       Light::point(Vec3(1.5 * u(rng), 1.5 * u(rng), 1.0 + 0.8 * u(rng)))});
  }
  report("rounded tile eta 1.5", run(tile, 1.5, queries));
}

}  // namespace
}  // namespace scatterlab
