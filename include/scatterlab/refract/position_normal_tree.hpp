#pragma once
// The position-normal tree of Walter et al. 2009, §3.4: a binary tree over the boundary
// triangles whose nodes bound positions (a box) and shading normals (a cone), pruned per query by
// the spindle, sidedness and cone-overlap tests.

#include <cstdint>
#include <vector>

#include "scatterlab/refract/bounding_cone.hpp"
#include "scatterlab/refract/triangle_search.hpp"

namespace scatterlab {

class PositionNormalTree {
 public:
  struct Node {
    Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();  // position bounds
    DirectionCone normals;                       // shading-normal bounds
    std::uint32_t first = 0;  // leaf: first triangle in order(); inner: right child (left = +1)
    std::uint32_t count = 0;  // leaf: number of triangles; inner: 0
  };

  PositionNormalTree() = default;
  explicit PositionNormalTree(const std::vector<RefractiveTriangle>& triangles);

  const std::vector<Node>& nodes() const { return nodes_; }
  const std::vector<std::uint32_t>& order() const { return order_; }

  // Whether a node may hold a path for the query (the three tests of §3.4).
  static bool may_contain_path(const Node& node, const PathQuery& q);

  // Calls visit(triangle_index) for every triangle of every leaf that survives pruning.
  template <class Visit>
  void for_each_candidate(const PathQuery& q, RefractionStats& stats, Visit&& visit) const {
    if (nodes_.empty()) return;
    std::uint32_t stack[64];
    int size = 0;
    stack[size++] = 0;
    while (size > 0) {
      const std::uint32_t index = stack[--size];
      const Node& node = nodes_[index];
      ++stats.nodes_visited;
      if (!may_contain_path(node, q)) continue;
      if (node.count > 0) {
        for (std::uint32_t i = 0; i < node.count; ++i) visit(order_[node.first + i]);
      } else {
        stack[size++] = node.first;
        stack[size++] = index + 1;
      }
    }
  }

 private:
  std::uint32_t build(const std::vector<RefractiveTriangle>& triangles, std::uint32_t begin,
                      std::uint32_t end, int depth);
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> order_;
};

}  // namespace scatterlab
