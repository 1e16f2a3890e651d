#pragma once
// All refracted single-scatter connections V <- P <- L through a triangle-mesh boundary
// (Walter et al. 2009, §3), and the light each carries (§4).

#include <vector>

#include "scatterlab/core/triangle_mesh.hpp"
#include "scatterlab/refract/position_normal_tree.hpp"
#include "scatterlab/refract/refraction_path.hpp"
#include "scatterlab/refract/triangle_search.hpp"

namespace scatterlab {

class RefractiveSolver {
 public:
  // eta = eta_inside / eta_outside > 0; throws InputError for a bad mesh or eta.
  RefractiveSolver(const TriangleMesh& mesh, double eta, RefractionOptions options = {});

  // Every path from the light to V (V inside the medium, the light outside); duplicates that
  // fall on shared edges are merged. Work is added to `stats`.
  void find_paths(const Vec3& v, const Light& light, std::vector<RefractionPath>& paths,
                  RefractionStats& stats) const;
  std::vector<RefractionPath> find_paths(const Vec3& v, const Light& light) const;

  double eta() const { return eta_; }
  const RefractionOptions& options() const { return options_; }
  void set_options(const RefractionOptions& options) { options_ = options; }
  const RefractiveTriangle& triangle(std::size_t index) const { return triangles_[index]; }
  std::size_t triangle_count() const { return triangles_.size(); }
  const PositionNormalTree& tree() const { return tree_; }

 private:
  void search_triangle(const RefractiveTriangle& tri, const PathQuery& q,
                       std::vector<RefractionPath>& paths, RefractionStats& stats) const;

  double eta_;
  RefractionOptions options_;
  std::vector<RefractiveTriangle> triangles_;
  PositionNormalTree tree_;
  double merge_distance_;  // paths closer than this are one path (1e-9 of the mesh size)
};

}  // namespace scatterlab
