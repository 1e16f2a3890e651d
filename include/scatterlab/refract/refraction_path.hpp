#pragma once
// The refractive connection problem of Walter et al. 2009, §3: a scattering point V inside a
// medium of relative index eta = eta_in / eta_out bounded by a triangle mesh, a light outside,
// and the boundary points P through which light refracts from the light to V.

#include <cstddef>
#include <cstdint>

#include "scatterlab/core/frame.hpp"

namespace scatterlab {

// A point light at `position`, or a directional light (at infinity) whose light arrives
// travelling along -direction_to_light.
struct Light {
  Vec3 position = Vec3::Zero();
  Vec3 direction_to_light = Vec3::UnitZ();  // unit; used when at_infinity
  bool at_infinity = false;

  static Light point(const Vec3& p) { return {p, Vec3::UnitZ(), false}; }
  static Light directional(const Vec3& towards_light) {
    return {Vec3::Zero(), towards_light.normalized(), true};
  }
  // Unit direction from p towards the light (omega_L of Walter eq. 2).
  Vec3 direction_from(const Vec3& p) const {
    return at_infinity ? direction_to_light : Vec3((position - p).normalized());
  }
};

// One refracted path V <- P <- L.
struct RefractionPath {
  Vec3 point;           // P on the boundary
  Vec3 shading_normal;  // unit outward N_s at P
  Vec3 omega_v;         // unit (V - P) / |V - P|, Walter eq. 1
  Vec3 omega_l;         // unit (L - P) / |L - P| (or the light direction), Walter eq. 2
  double distance_v = 0.0;  // |V - P|
  double distance_l = 0.0;  // |L - P| (infinity for a directional light)
  std::uint32_t triangle = 0;
  double bary_a = 0.0, bary_b = 0.0;  // P = (1 - a - b) p0 + a p1 + b p2
};

enum class SearchMode {
  heuristic,   // split until the H and N cone angles sum below 30 degrees (Walter §3.3.1)
  guaranteed,  // split until the Krawczyk test decides (Walter §3.3.2)
};

struct RefractionOptions {
  SearchMode mode = SearchMode::heuristic;
  double newton_tolerance = 1e-12;  // |f| at which Newton stops (Walter eq. 8 residual)
  int max_newton_iterations = 50;
  double cone_stop_angle = 0.5235987755982988;  // 30 degrees, Walter §3.3.1
  int max_split_depth = 12;  // sub-triangle splits at most (a safety net; counted when hit)
  bool use_tree = true;      // position-normal tree (Walter §3.4) or every triangle
};

// Work counters, summed over queries: the figures the benchmarks report.
struct RefractionStats {
  std::uint64_t queries = 0;
  std::uint64_t nodes_visited = 0;
  std::uint64_t triangles_tested = 0;  // triangles handed to the per-triangle search
  std::uint64_t subtriangles = 0;
  std::uint64_t newton_runs = 0;
  std::uint64_t newton_iterations = 0;
  std::uint64_t undecided_at_depth_limit = 0;  // guaranteed mode: split limit reached
  std::uint64_t paths = 0;

  RefractionStats& operator+=(const RefractionStats& o) {
    queries += o.queries;
    nodes_visited += o.nodes_visited;
    triangles_tested += o.triangles_tested;
    subtriangles += o.subtriangles;
    newton_runs += o.newton_runs;
    newton_iterations += o.newton_iterations;
    undecided_at_depth_limit += o.undecided_at_depth_limit;
    paths += o.paths;
    return *this;
  }
};

}  // namespace scatterlab
