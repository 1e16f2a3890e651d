#include "scatterlab/refract/refractive_solver.hpp"

#include <cmath>

#include <fmt/format.h>

#include "scatterlab/core/error.hpp"

namespace scatterlab {

RefractiveSolver::RefractiveSolver(const TriangleMesh& mesh, double eta, RefractionOptions options)
    : eta_(eta), options_(options) {
  if (!(eta > 0.0) || !std::isfinite(eta)) {
    throw InputError("eta", fmt::format("got {}", eta), "a finite number > 0");
  }
  mesh.validate();
  triangles_.reserve(mesh.triangle_count());
  merge_distance_ = 1e-9 * std::max(mesh.bounds().diagonal(), 1e-300);
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    triangles_.push_back(RefractiveTriangle::from_mesh(mesh, t));
  }
  tree_ = PositionNormalTree(triangles_);
}

void RefractiveSolver::search_triangle(const RefractiveTriangle& tri, const PathQuery& q,
                                       std::vector<RefractionPath>& paths,
                                       RefractionStats& stats) const {
  ++stats.triangles_tested;
  if (auto on = path_with_v_on_triangle(tri, q)) {
    paths.push_back(*on);
    return;
  }
  if (q.eta == 1.0) {
    if (auto path = find_straight_path(tri, q)) paths.push_back(*path);
  } else if (!tri.smooth) {
    if (auto path = find_flat_path(tri, q, stats)) paths.push_back(*path);
  } else {
    find_smooth_paths(tri, q, options_, stats, paths);
  }
}

void RefractiveSolver::find_paths(const Vec3& v, const Light& light,
                                  std::vector<RefractionPath>& paths,
                                  RefractionStats& stats) const {
  const std::size_t first = paths.size();
  const PathQuery q(v, light, eta_);
  ++stats.queries;
  if (options_.use_tree) {
    tree_.for_each_candidate(q, stats, [&](std::uint32_t t) {
      search_triangle(triangles_[t], q, paths, stats);
    });
  } else {
    for (const RefractiveTriangle& tri : triangles_) search_triangle(tri, q, paths, stats);
  }
  merge_duplicates(paths, first, stats);
}

void RefractiveSolver::find_paths_through(std::size_t triangle, const Vec3& v, const Light& light,
                                          std::vector<RefractionPath>& paths,
                                          RefractionStats& stats) const {
  search_triangle(triangles_[triangle], PathQuery(v, light, eta_), paths, stats);
}

void RefractiveSolver::merge_duplicates(std::vector<RefractionPath>& paths, std::size_t first,
                                        RefractionStats& stats) const {
  // Merge the copies a solution on a shared edge (or found from two sub-triangles) produces.
  std::size_t kept = first;
  for (std::size_t i = first; i < paths.size(); ++i) {
    bool duplicate = false;
    for (std::size_t j = first; j < kept && !duplicate; ++j) {
      duplicate = (paths[i].point - paths[j].point).norm() <= merge_distance_;
    }
    if (!duplicate) paths[kept++] = paths[i];
  }
  paths.resize(kept);
  stats.paths += kept - first;
}

std::vector<RefractionPath> RefractiveSolver::find_paths(const Vec3& v, const Light& light) const {
  std::vector<RefractionPath> paths;
  RefractionStats stats;
  find_paths(v, light, paths, stats);
  return paths;
}

}  // namespace scatterlab
