// Holzschuch 2013 §3.2: per-triangle support intervals along an eye ray and the pruning of a
// whole segment. Every x at which a triangle contributes (dense sampling with the path finder)
// must lie in its interval; flat triangles' intervals must be exact (the triangle contributes
// just inside both ends) and smooth ones tight (Holzschuch's shading-normal test); and single
// scattering integrated over the intervals only must equal the integral over the whole segment
// with the same sample points.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <random>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/refract/path_contribution.hpp"
#include "scatterlab/refract/support_interval.hpp"

namespace scatterlab {
namespace {

struct Case {
  const char* name;
  TriangleMesh mesh;
  double eta;
  bool directional;
  bool tile;  // segments and lights for the rounded tile, else for a unit sphere
};

struct RayCase {
  EyeSegment segment;
  Light light;
};

// Random chords inside the medium (a ball of radius 0.8, or a slab of the tile) and lights
// outside it.
std::vector<RayCase> make_ray_cases(const Case& c, int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto inside = [&]() -> Vec3 {
    if (c.tile) return {0.7 * u(rng), 0.7 * u(rng), 0.15 * u(rng)};
    return 0.8 * std::cbrt(0.5 + 0.5 * u(rng)) *
           Vec3(normal(rng), normal(rng), normal(rng)).normalized();
  };
  std::vector<RayCase> ray_cases;
  for (int i = 0; i < count; ++i) {
    const Vec3 a = inside(), b = inside();
    RayCase s;
    s.segment = {a, (b - a).normalized(), 0.0, (b - a).norm()};
    const Vec3 dl = c.tile ? Vec3(0.8 * u(rng), 0.8 * u(rng), 1.0).normalized()
                           : Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    s.light = c.directional ? Light::directional(dl)
                            : Light::point((c.tile ? 1.6 : 2.0 + u(rng)) * dl);
    ray_cases.push_back(s);
  }
  return ray_cases;
}

const SupportInterval* find_support(const std::vector<TriangleSupport>& supports,
                                    std::uint32_t triangle) {
  for (const TriangleSupport& s : supports) {
    if (s.triangle == triangle) return &s.interval;
  }
  return nullptr;
}

class SupportContainment : public ::testing::TestWithParam<int> {};

std::vector<Case> cases() {
  std::vector<Case> list;
  list.push_back({"flat sphere, eta 1.5", make_sphere(1.0, 16, 32, false), 1.5, false, false});
  list.push_back({"flat sphere, eta 0.75", make_sphere(1.0, 16, 32, false), 0.75, false, false});
  list.push_back({"flat sphere, directional", make_sphere(1.0, 16, 32, false), 1.5, true, false});
  list.push_back({"flat sphere, eta 1", make_sphere(1.0, 16, 32, false), 1.0, false, false});
  list.push_back({"smooth sphere, eta 1.5", make_sphere(1.0, 12, 24, true), 1.5, false, false});
  list.push_back({"smooth sphere, eta 0.75", make_sphere(1.0, 12, 24, true), 0.75, false, false});
  list.push_back({"bumpy sphere, eta 1.5", make_bumpy_sphere(1.0, 0.05, 6, 71, 72), 1.5, false,
                  false});
  list.push_back({"rounded tile, eta 1.5", make_rounded_tile(1.0, 1.0, 0.25, 0.3, 16, 32), 1.5,
                  false, true});
  list.push_back({"rounded tile, eta 0.75", make_rounded_tile(1.0, 1.0, 0.25, 0.3, 16, 32),
                  0.75, false, true});
  return list;
}

// Dense sampling: at every sample, each path the solver finds must come through a triangle whose
// interval holds the sample. Reports how short the intervals are and how many triangles survive.
TEST_P(SupportContainment, IntervalsHoldEverySampleAtWhichATriangleContributes) {
  const Case c = cases()[static_cast<std::size_t>(GetParam())];
  const RefractiveSolver solver(c.mesh, c.eta);
  const bool bumpy = solver.triangle_count() > 5000;
  const bool smooth = c.mesh.has_shading_normals();  // the 2D search is slower
  const int samples = bumpy ? 250 : (smooth ? 250 : 600);
  // Per triangle, the span of the samples at which it contributed: tightness of the intervals.
  std::vector<double> first_x(solver.triangle_count()), last_x(solver.triangle_count());
  double observed_span = 0.0, span_interval_length = 0.0;
  std::size_t contributions = 0, outside = 0, supports_total = 0;
  double relative_length = 0.0;
  SupportStats stats;
  const auto ray_cases = make_ray_cases(c, bumpy ? 3 : 5, 29 + static_cast<std::uint64_t>(GetParam()));
  for (const RayCase& s : ray_cases) {
    std::vector<TriangleSupport> supports;
    find_segment_supports(RefractedLight(solver, s.light), s.segment, supports, stats);
    supports_total += supports.size();
    for (const TriangleSupport& t : supports) {
      relative_length += t.interval.length() / (s.segment.t1 - s.segment.t0);
    }
    std::fill(first_x.begin(), first_x.end(), std::numeric_limits<double>::infinity());
    std::fill(last_x.begin(), last_x.end(), -std::numeric_limits<double>::infinity());
    for (int i = 0; i < samples; ++i) {
      const double x = s.segment.t0 + (s.segment.t1 - s.segment.t0) * (i + 0.5) / samples;
      for (const RefractionPath& p : solver.find_paths(s.segment.at(x), s.light)) {
        ++contributions;
        first_x[p.triangle] = std::min(first_x[p.triangle], x);
        last_x[p.triangle] = std::max(last_x[p.triangle], x);
        const SupportInterval* interval = find_support(supports, p.triangle);
        if (interval == nullptr || !interval->contains(x)) {
          ++outside;
          ADD_FAILURE() << c.name << ": triangle " << p.triangle << " contributes at x = " << x
                        << " outside its interval";
        }
      }
    }
    for (const TriangleSupport& t : supports) {
      if (!(last_x[t.triangle] >= first_x[t.triangle])) continue;
      observed_span += last_x[t.triangle] - first_x[t.triangle];
      span_interval_length += t.interval.length();
    }
  }
  EXPECT_EQ(outside, 0u);
  EXPECT_GT(contributions, 0u) << c.name << ": no contribution sampled, the test would be empty";
  const double pruned = 1.0 - double(supports_total) /
                                  double(ray_cases.size() * solver.triangle_count());
  const double mean_length = supports_total > 0 ? relative_length / double(supports_total) : 0.0;
  std::cout << "[ support  ] " << c.name << ": " << contributions << " sampled contributions, "
            << double(supports_total) / double(ray_cases.size()) << " of "
            << solver.triangle_count() << " triangles kept per segment (" << 100.0 * pruned
            << " % pruned), mean interval " << 100.0 * mean_length << " % of the segment, "
            << "sampled support / interval " << observed_span / span_interval_length << ", "
            << stats.edge_newton_runs << " edge Newton crossings, " << stats.edge_bisections
            << " bisections\n";
  RecordProperty("pruned_fraction", std::to_string(pruned));
  RecordProperty("mean_interval_fraction", std::to_string(mean_length));
  EXPECT_GT(pruned, 0.8);  // not vacuous: most triangles cannot reach a given segment
  // Flat intervals are exact; interpolated normals' come from the shading-normal test (measured
  // 0.68-0.94 of the interval sampled; 0.16-0.45 with step 2's cone bound alone).
  EXPECT_LT(mean_length, smooth ? 0.4 : 0.2);
  EXPECT_GT(observed_span / span_interval_length, smooth ? 0.6 : 0.95);
}

INSTANTIATE_TEST_SUITE_P(Meshes, SupportContainment, ::testing::Range(0, 9));

// Flat triangles (and eta = 1): the interval is exact, so the triangle contributes just inside
// both of its ends.
TEST(SupportInterval, FlatIntervalsAreExact) {
  for (const double eta : {1.5, 0.75, 1.0}) {
    for (const bool directional : {false, true}) {
      const Case c{"flat", make_sphere(1.0, 10, 20, false), eta, directional, false};
      const RefractiveSolver solver(c.mesh, eta);
      std::size_t checked = 0;
      for (const RayCase& s : make_ray_cases(c, 6, 71)) {
        std::vector<TriangleSupport> supports;
        SupportStats stats;
        find_segment_supports(RefractedLight(solver, s.light), s.segment, supports, stats);
        for (const TriangleSupport& t : supports) {
          const double nudge = 1e-7 * (s.segment.t1 - s.segment.t0);
          if (!(t.interval.length() > 4.0 * nudge)) continue;
          for (const double x : {t.interval.x_min + nudge, t.interval.x_max - nudge}) {
            std::vector<RefractionPath> paths;
            RefractionStats rs;
            solver.find_paths_through(t.triangle, s.segment.at(x), s.light, paths, rs);
            EXPECT_EQ(paths.size(), 1u) << "eta " << eta << " directional " << directional
                                        << ": triangle " << t.triangle << " silent at x = " << x
                                        << " inside [" << t.interval.x_min << ", "
                                        << t.interval.x_max << "]";
            ++checked;
          }
        }
      }
      EXPECT_GT(checked, 10u);
    }
  }
}

// Single scattering along the ray (isotropic phase, sigma_t = 0.7): summing only over the
// triangles whose intervals hold each sample equals the full search at every sample.
TEST(SupportInterval, IntegralOverIntervalsEqualsIntegralOverSegment) {
  for (const bool smooth : {false, true}) {
    const Case c{"integral", smooth ? make_bumpy_sphere(1.0, 0.05, 6, 35, 36)
                                    : make_sphere(1.0, 16, 32, false),
                 1.5, false, false};
    const RefractiveSolver solver(c.mesh, c.eta);
    const double sigma_t = 0.7, phase = 1.0 / (4.0 * pi);
    const int samples = 200;
    std::size_t whole_searches = 0, interval_searches = 0;
    for (const RayCase& s : make_ray_cases(c, 3, 5)) {
      std::vector<TriangleSupport> supports;
      SupportStats stats;
      find_segment_supports(RefractedLight(solver, s.light), s.segment, supports, stats);
      const double dx = (s.segment.t1 - s.segment.t0) / samples;
      double whole = 0.0, restricted = 0.0;
      std::vector<RefractionPath> paths;
      for (int i = 0; i < samples; ++i) {
        const double x = s.segment.t0 + dx * (i + 0.5);
        const Vec3 v = s.segment.at(x);
        const double to_eye = std::exp(-sigma_t * (x - s.segment.t0));
        RefractionStats full;
        paths.clear();
        solver.find_paths(v, s.light, paths, full);
        whole_searches += full.triangles_tested;
        for (const RefractionPath& p : paths) {
          whole += dx * to_eye * phase *
                   path_contribution(solver.triangle(p.triangle), p, c.eta, sigma_t, false)
                       .irradiance;
        }
        RefractionStats part;
        paths.clear();
        for (const TriangleSupport& t : supports) {
          if (t.interval.contains(x)) solver.find_paths_through(t.triangle, v, s.light, paths, part);
        }
        solver.merge_duplicates(paths, 0, part);
        interval_searches += part.triangles_tested;
        for (const RefractionPath& p : paths) {
          restricted += dx * to_eye * phase *
                        path_contribution(solver.triangle(p.triangle), p, c.eta, sigma_t, false)
                            .irradiance;
        }
      }
      EXPECT_GT(whole, 0.0);
      EXPECT_NEAR(restricted, whole, 1e-13 * whole) << (smooth ? "bumpy" : "flat");
    }
    std::cout << "[ support  ] " << (smooth ? "bumpy" : "flat") << " sphere: triangle searches "
              << whole_searches << " with the tree at every sample, " << interval_searches
              << " inside the intervals\n";
    EXPECT_LT(interval_searches, whole_searches);
  }
}

TEST(SupportInterval, RejectsBadSegments) {
  const RefractiveSolver solver(make_sphere(1.0, 6, 12, false), 1.5);
  std::vector<TriangleSupport> supports;
  SupportStats stats;
  const Light light = Light::point(Vec3(0, 0, 3));
  const RefractedLight lit(solver, light);
  EXPECT_THROW(find_segment_supports(lit, {Vec3::Zero(), Vec3(2, 0, 0), 0.0, 0.5}, supports, stats),
               InputError);
  EXPECT_THROW(find_segment_supports(lit, {Vec3::Zero(), Vec3::UnitX(), 0.5, 0.0}, supports, stats),
               InputError);
}

}  // namespace
}  // namespace scatterlab
